// --bond-filters FILE: the JSON array of rectangles and disks of bond_filter.hpp, checked key by
// key so that every error names the file, the filter and the key.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "horizon/bond_filter.hpp"
#include "horizon/error.hpp"

namespace horizon {

namespace {

class FilterReader {
public:
  FilterReader(const std::string& path, std::size_t index, const nlohmann::json& object)
      : where_(path + ": filter " + std::to_string(index)), object_(object) {}

  [[noreturn]] void fail(const std::string& what) const { throw Error(where_ + ": " + what); }

  static std::string quoted(const char* key) {  // built by append: GCC 12 warns (-Wrestrict) on "'" + key
    std::string text(1, '\'');
    text.append(key).push_back('\'');
    return text;
  }

  const nlohmann::json& field(const char* key) const {
    if (!object_.contains(key)) fail("missing key '" + std::string(key) + "'");
    return object_.at(key);
  }

  double number(const char* key, bool positive) const {
    const nlohmann::json& value = field(key);
    if (!value.is_number()) fail(quoted(key) + " must be a number");
    const double x = value.get<double>();
    if (!std::isfinite(x) || (positive && !(x > 0))) fail(quoted(key) + " must be finite and > 0");
    return x;
  }

  std::array<double, 3> vector(const char* key, bool unit) const {
    const nlohmann::json& value = field(key);
    if (!value.is_array() || value.size() != 3) fail(quoted(key) + " must be an array of 3 numbers");
    std::array<double, 3> v{};
    for (int a = 0; a < 3; ++a) {
      if (!value[a].is_number()) fail(quoted(key) + " must be an array of 3 numbers");
      v[a] = value[a].get<double>();
      if (!std::isfinite(v[a])) fail(quoted(key) + " must be finite");
    }
    if (unit) {
      // Scaled first, so that components near the largest double do not overflow the length.
      const double largest = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
      if (largest > 0)
        for (double& x : v) x /= largest;
      const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (!(length > 0)) fail(quoted(key) + " must not be the zero vector");
      for (double& x : v) x /= length;
    }
    return v;
  }

private:
  std::string where_;
  const nlohmann::json& object_;
};

BondFilter read_filter(const FilterReader& in, const nlohmann::json& object) {
  if (!object.is_object()) in.fail("expected an object with a \"type\"");
  const nlohmann::json& type = in.field("type");
  if (type == "rectangle") {
    RectangleFilter f{in.vector("normal", true), in.vector("lower_left_corner", false),
                      in.vector("bottom_unit_vector", true), in.number("bottom_length", true),
                      in.number("side_length", true)};
    const double along = (f.normal[0] * f.bottom_unit_vector[0] + f.normal[1] * f.bottom_unit_vector[1]) +
                         f.normal[2] * f.bottom_unit_vector[2];
    if (std::abs(along) > 1e-9) in.fail("'bottom_unit_vector' must be perpendicular to 'normal'");
    return f;
  }
  if (type == "disk") return DiskFilter{in.vector("center", false), in.vector("normal", true), in.number("radius", true)};
  in.fail("'type' must be \"rectangle\" or \"disk\", not " + type.dump());
}

}  // namespace

std::vector<BondFilter> parse_bond_filters(const std::string& json, const std::string& source) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(json);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for huge numbers
    throw Error(source + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  if (!document.is_array()) throw Error(source + ": expected a JSON array of filters");
  if (document.size() > max_bond_filters)
    throw Error(source + ": " + std::to_string(document.size()) + " filters, at most " +
                std::to_string(max_bond_filters) + " are supported");
  std::vector<BondFilter> filters;
  for (std::size_t i = 0; i < document.size(); ++i)
    filters.push_back(read_filter(FilterReader(source, i, document[i]), document[i]));
  return filters;
}

std::vector<BondFilter> read_bond_filters(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw Error(path + ": cannot read the bond filters (no such file?)");
  return parse_bond_filters(std::string(std::istreambuf_iterator<char>(file), {}), path);
}

}  // namespace horizon
