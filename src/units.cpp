#include "mpmshock/units.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace mpmshock {
namespace {

// value_si = value * multiply / divide. Both factors are exact powers of ten, so the result is the
// correctly rounded SI value: "50 um" gives exactly the double 50e-6.
struct Unit {
  std::string_view name;
  Dimension dim;
  double multiply, divide;
};

// Spellings a physicist writes. Order matters only for accepted_units() listings.
constexpr std::array<Unit, 38> kUnits{{
    {"m", Dimension::length, 1, 1},
    {"cm", Dimension::length, 1, 1e2},
    {"mm", Dimension::length, 1, 1e3},
    {"um", Dimension::length, 1, 1e6},
    {"µm", Dimension::length, 1, 1e6},
    {"nm", Dimension::length, 1, 1e9},
    {"s", Dimension::time, 1, 1},
    {"ms", Dimension::time, 1, 1e3},
    {"us", Dimension::time, 1, 1e6},
    {"µs", Dimension::time, 1, 1e6},
    {"ns", Dimension::time, 1, 1e9},
    {"ps", Dimension::time, 1, 1e12},
    {"m/s", Dimension::speed, 1, 1},
    {"km/s", Dimension::speed, 1e3, 1},
    {"mm/us", Dimension::speed, 1e3, 1},
    {"um/ns", Dimension::speed, 1e3, 1},
    {"cm/us", Dimension::speed, 1e4, 1},
    {"Pa", Dimension::pressure, 1, 1},
    {"kPa", Dimension::pressure, 1e3, 1},
    {"MPa", Dimension::pressure, 1e6, 1},
    {"GPa", Dimension::pressure, 1e9, 1},
    {"bar", Dimension::pressure, 1e5, 1},
    {"kbar", Dimension::pressure, 1e8, 1},
    {"Mbar", Dimension::pressure, 1e11, 1},
    {"kg/m3", Dimension::density, 1, 1},
    {"kg/m^3", Dimension::density, 1, 1},
    {"g/cm3", Dimension::density, 1e3, 1},
    {"g/cm^3", Dimension::density, 1e3, 1},
    {"g/cc", Dimension::density, 1e3, 1},
    {"K", Dimension::temperature, 1, 1},
    {"J/(kg K)", Dimension::specific_heat, 1, 1},
    {"J/kg/K", Dimension::specific_heat, 1, 1},
    {"J/(kg*K)", Dimension::specific_heat, 1, 1},
    {"W/(m K)", Dimension::conductivity, 1, 1},
    {"W/m/K", Dimension::conductivity, 1, 1},
    {"J/kg", Dimension::specific_energy, 1, 1},
    {"kJ/kg", Dimension::specific_energy, 1e3, 1},
    {"MJ/kg", Dimension::specific_energy, 1e6, 1},
}};

std::string_view dimension_word(Dimension dim) {
  switch (dim) {
    case Dimension::none: return "a pure number";
    case Dimension::length: return "a length";
    case Dimension::time: return "a time";
    case Dimension::speed: return "a speed";
    case Dimension::pressure: return "a pressure";
    case Dimension::density: return "a density";
    case Dimension::temperature: return "a temperature";
    case Dimension::specific_heat: return "a specific heat";
    case Dimension::conductivity: return "a thermal conductivity";
    case Dimension::specific_energy: return "an energy per mass";
  }
  return "?";
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Splits "12.5mm" / "12.5 mm" into the number and the unit text.
std::pair<std::string_view, std::string_view> split_number_unit(std::string_view text) {
  std::size_t i = 0;
  auto digit = [&](std::size_t k) { return k < text.size() && std::isdigit(static_cast<unsigned char>(text[k])); };
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  while (digit(i)) ++i;
  if (i < text.size() && text[i] == '.') ++i;
  while (digit(i)) ++i;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    std::size_t k = i + 1;
    if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
    if (digit(k)) {
      i = k;
      while (digit(i)) ++i;
    }
  }
  return {text.substr(0, i), trim(text.substr(i))};
}

}  // namespace

std::string plain_spacing(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  const auto byte = [&](std::size_t k) { return k < text.size() ? static_cast<unsigned char>(text[k]) : 0u; };
  for (std::size_t k = 0; k < text.size();) {
    const unsigned a = byte(k), b = byte(k + 1), c = byte(k + 2);
    std::size_t space = 0;  // the UTF-8 length of a space character here
    if (a == 0xC2 && b == 0xA0) space = 2;                                      // U+00A0
    else if (a == 0xE1 && b == 0x9A && c == 0x80) space = 3;                    // U+1680
    else if (a == 0xE2 && b == 0x80 && ((c >= 0x80 && c <= 0x8A) || c == 0xAF)) space = 3;  // U+2000-200A, 202F
    else if (a == 0xE2 && b == 0x81 && c == 0x9F) space = 3;                    // U+205F
    else if (a == 0xE3 && b == 0x80 && c == 0x80) space = 3;                    // U+3000
    if (space) {
      out += ' ';
      k += space;
    } else if (a == 0xCE && b == 0xBC) {  // Greek mu
      out += "\xC2\xB5";
      k += 2;
    } else {
      out += text[k++];
    }
  }
  return out;
}

std::string_view si_unit(Dimension dim) {
  switch (dim) {
    case Dimension::none: return "";
    case Dimension::length: return "m";
    case Dimension::time: return "s";
    case Dimension::speed: return "m/s";
    case Dimension::pressure: return "Pa";
    case Dimension::density: return "kg/m3";
    case Dimension::temperature: return "K";
    case Dimension::specific_heat: return "J/(kg K)";
    case Dimension::conductivity: return "W/(m K)";
    case Dimension::specific_energy: return "J/kg";
  }
  return "";
}

std::string accepted_units(Dimension dim) {
  std::string out;
  for (const Unit& u : kUnits) {
    if (u.dim != dim) continue;
    if (!out.empty()) out += ", ";
    out += u.name;
  }
  if (out.find("\xC2\xB5") != std::string::npos) out += " (\xC2\xB5: the micro sign or the Greek mu)";
  return out.empty() ? std::string("no unit") : out;
}

double parse_number(std::string_view raw) {
  const std::string plain = plain_spacing(raw);
  std::string_view text = trim(plain);
  if (text.empty()) throw std::invalid_argument("missing value");
  auto [number, rest] = split_number_unit(text);
  if (number.empty() || number == "+" || number == "-" || number == "." || !rest.empty())
    throw std::invalid_argument("'" + std::string(text) + "' is not a number");
  if (number.front() == '+') number.remove_prefix(1);
  double value = 0.0;
  auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && !std::isfinite(value)))
    throw std::invalid_argument("'" + std::string(text) + "' is out of the range of a double");
  if (ec != std::errc() || ptr != number.data() + number.size())
    throw std::invalid_argument("'" + std::string(text) + "' is not a number");
  return value;
}

double parse_quantity(std::string_view raw, Dimension dim) {
  const std::string plain = plain_spacing(raw);
  std::string_view text = trim(plain);
  if (text.empty()) throw std::invalid_argument("missing value");
  auto [number, unit] = split_number_unit(text);
  if (number.empty() || number == "+" || number == "-")
    throw std::invalid_argument("'" + std::string(text) + "' is not a number");
  const double value = parse_number(number);
  if (unit.empty()) return value;
  for (const Unit& u : kUnits) {
    if (u.name != unit) continue;
    if (u.dim != dim) {
      std::string msg = "unit '" + std::string(unit) + "' is " + std::string(dimension_word(u.dim)) +
                        ", but this key takes " + std::string(dimension_word(dim));
      if (dim != Dimension::none) msg += " (" + accepted_units(dim) + ")";
      throw std::invalid_argument(msg);
    }
    const double si = u.divide == 1 ? value * u.multiply : value / u.divide;
    if (!std::isfinite(si)) throw std::invalid_argument("'" + std::string(text) + "' overflows in SI units");
    return si;
  }
  std::string msg = "unknown unit '" + std::string(unit) + "'";
  msg += dim == Dimension::none ? std::string("; this key takes a pure number")
                                : "; this key takes " + std::string(dimension_word(dim)) + " in " + accepted_units(dim);
  throw std::invalid_argument(msg);
}

std::string format_number(double v) {
  char buf[64];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);  // shortest text that reads back exactly
  return ec == std::errc() ? std::string(buf, ptr) : std::string("nan");
}

}  // namespace mpmshock
