#include "membrane_law.h"

#include <stdexcept>

namespace rbcflow {
namespace {

void require_positive(double v, const char* what) {
  if (!(v > 0)) throw std::invalid_argument(std::string("membrane law: ") + what + " must be positive");
}

}  // namespace

SkalakLaw::SkalakLaw(double shear_modulus, double dilatation_modulus)
    : es_(shear_modulus), ed_(dilatation_modulus) {
  require_positive(es_, "shear modulus");
  if (ed_ < 0) throw std::invalid_argument("membrane law: dilatation modulus must be >= 0");
}

StrainEnergy SkalakLaw::energy(double I1, double I2) const {
  return {0.25 * es_ * (0.5 * I1 * I1 + I1 - I2) + 0.125 * ed_ * I2 * I2,  //
          0.25 * es_ * (I1 + 1.0),                                          //
          -0.25 * es_ + 0.25 * ed_ * I2};
}

NeoHookeanLaw::NeoHookeanLaw(double shear_modulus) : gs_(shear_modulus) {
  require_positive(gs_, "shear modulus");
}

StrainEnergy NeoHookeanLaw::energy(double I1, double I2) const {
  const double j2 = I2 + 1.0;
  return {0.5 * gs_ * (I1 + 1.0 / j2 - 1.0), 0.5 * gs_, -0.5 * gs_ / (j2 * j2)};
}

HookeanLaw::HookeanLaw(double shear_modulus, double dilatation_modulus)
    : es_(shear_modulus), ed_(dilatation_modulus) {
  require_positive(es_, "shear modulus");
  if (ed_ < 0) throw std::invalid_argument("membrane law: dilatation modulus must be >= 0");
}

StrainEnergy HookeanLaw::energy(double I1, double I2) const {
  return {0.125 * ed_ * I1 * I1 + 0.25 * es_ * (I1 * I1 + 2.0 * I1 - 2.0 * I2),  //
          0.25 * ed_ * I1 + 0.5 * es_ * (I1 + 1.0),                             //
          -0.5 * es_};
}

std::unique_ptr<MembraneLaw> make_membrane_law(std::string_view name, double shear_modulus,
                                               double dilatation_modulus) {
  if (name == "skalak") return std::make_unique<SkalakLaw>(shear_modulus, dilatation_modulus);
  if (name == "neo-hookean") return std::make_unique<NeoHookeanLaw>(shear_modulus);
  if (name == "hookean") return std::make_unique<HookeanLaw>(shear_modulus, dilatation_modulus);
  throw std::invalid_argument("unknown membrane law '" + std::string(name) +
                              "' (expected skalak, neo-hookean or hookean)");
}

}  // namespace rbcflow
