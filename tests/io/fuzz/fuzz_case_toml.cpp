// libFuzzer target for the case parser: any input either reads as a case or throws CaseError
// (never crashes, hangs or trips a sanitizer), and a case that reads writes back to TOML that
// reads as the same case.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "io/case.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rbcflow::Case c;
  try {
    c = rbcflow::parse_case(text, "fuzz.toml");
  } catch (const rbcflow::CaseError&) {
    return 0;
  }
  const rbcflow::Case back = rbcflow::parse_case(rbcflow::case_toml(c), "fuzz.toml");
  if (!(back == c)) std::abort();
  return 0;
}
