#pragma once
// In-plane constitutive laws of an isotropic hyperelastic membrane, W(I1, I2) per unit
// reference area with the strain invariants of eq. (18): I1 = l1^2 + l2^2 - 2,
// I2 = l1^2 l2^2 - 1. A law gives W and its derivatives W1 = dW/dI1, W2 = dW/dI2; the
// Cauchy tension follows for every law alike (membrane_force.h):
//   N^{ab} = (2 / J) W1 A^{ab} + 2 J W2 a^{ab},  J = l1 l2,
// which for the Skalak law reproduces eq. (20). New laws need only this interface.
#include <memory>
#include <string>
#include <string_view>

namespace rbcflow {

struct StrainEnergy {
  double W = 0;   // energy per unit reference area
  double W1 = 0;  // dW / dI1
  double W2 = 0;  // dW / dI2
};

class MembraneLaw {
 public:
  virtual ~MembraneLaw() = default;
  virtual StrainEnergy energy(double I1, double I2) const = 0;
  virtual std::string name() const = 0;
  // Small-strain surface shear and area-dilatation moduli (G_s, K_s) of the law, in the
  // convention W ~ (K_s / 2)(tr e)^2 + G_s e_dev : e_dev (docs/references.md section 4).
  virtual double small_strain_shear_modulus() const = 0;
  virtual double small_strain_area_modulus() const = 0;
};

// Skalak law (19): W = (E_S / 4)(I1^2 / 2 + I1 - I2) + (E_D / 8) I2^2.
// Small strain: G_s = E_S / 2, K_s = E_D + E_S / 2.
class SkalakLaw final : public MembraneLaw {
 public:
  SkalakLaw(double shear_modulus, double dilatation_modulus);
  StrainEnergy energy(double I1, double I2) const override;
  std::string name() const override { return "skalak"; }
  double small_strain_shear_modulus() const override { return es_ / 2; }
  double small_strain_area_modulus() const override { return ed_ + es_ / 2; }

 private:
  double es_, ed_;
};

// Neo-Hookean capsule law (Barthes-Biesel): W = (G_s / 2)(I1 + 1 / (I2 + 1) - 1).
// Small strain: G_s, K_s = 3 G_s. (No separate dilatation modulus.)
class NeoHookeanLaw final : public MembraneLaw {
 public:
  explicit NeoHookeanLaw(double shear_modulus);
  StrainEnergy energy(double I1, double I2) const override;
  std::string name() const override { return "neo-hookean"; }
  double small_strain_shear_modulus() const override { return gs_; }
  double small_strain_area_modulus() const override { return 3 * gs_; }

 private:
  double gs_;
};

// Hookean law (41) of section 9: W = (E_D / 2)(tr e)^2 + E_S tr(e^2), e = (C - I) / 2, i.e.
// W = E_D I1^2 / 8 + E_S (I1^2 + 2 I1 - 2 I2) / 4, whose tension is eq. (42).
// Small strain: G_s = E_S, K_s = E_D + E_S.
class HookeanLaw final : public MembraneLaw {
 public:
  HookeanLaw(double shear_modulus, double dilatation_modulus);
  StrainEnergy energy(double I1, double I2) const override;
  std::string name() const override { return "hookean"; }
  double small_strain_shear_modulus() const override { return es_; }
  double small_strain_area_modulus() const override { return ed_ + es_; }

 private:
  double es_, ed_;
};

// "skalak" | "neo-hookean" | "hookean"; the dilatation modulus is unused by neo-hookean.
std::unique_ptr<MembraneLaw> make_membrane_law(std::string_view name, double shear_modulus,
                                               double dilatation_modulus);

}  // namespace rbcflow
