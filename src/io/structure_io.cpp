// Atomistic structures: extended XYZ (ASE's and vesin's test data) and LAMMPS data files, each
// read into points, a cell and its pbc. Every error names the file, the line and the key.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "parse_number.hpp"

namespace horizon {
namespace {

std::string basename(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

/// A finite number, and nothing else.
bool number(const std::string& text, double& value) { return detail::parse_number(text, value) && std::isfinite(value); }

bool integer(const std::string& text, long long& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

/// The text file's lines (without their line ends).
std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// ---- extended XYZ -------------------------------------------------------------------------

/// The key=value pairs of an extended XYZ comment line (values quoted with "" or bare).
std::map<std::string, std::string> comment_pairs(const std::string& line, const std::string& where) {
  std::map<std::string, std::string> pairs;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i == line.size()) break;
    const std::size_t key_start = i;
    while (i < line.size() && line[i] != '=' && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::string key = line.substr(key_start, i - key_start);
    std::string value = "T";  // a bare key is a true flag
    if (i < line.size() && line[i] == '=') {
      ++i;
      if (i < line.size() && line[i] == '"') {
        const std::size_t close = line.find('"', i + 1);
        if (close == std::string::npos) throw Error(where + "key " + key + ": the quoted value is not closed");
        value = line.substr(i + 1, close - i - 1);
        i = close + 1;
      } else {
        const std::size_t start = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        value = line.substr(start, i - start);
      }
    }
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return std::tolower(c); });
    pairs[key] = value;
  }
  return pairs;
}

bool flag(const std::string& text, bool& value) {
  if (text == "T" || text == "True" || text == "true" || text == "1") return value = true, true;
  if (text == "F" || text == "False" || text == "false" || text == "0") return value = false, true;
  return false;
}

Structure read_extxyz(const std::string& path) {
  const std::vector<std::string> lines = lines_of(path);
  const auto at = [&](std::size_t line) { return path + ":" + std::to_string(line) + ": "; };
  long long count = -1;
  const std::vector<std::string> first = lines.empty() ? std::vector<std::string>{} : words(lines[0]);
  if (first.size() != 1 || !integer(first[0], count) || count < 0)
    throw Error(at(1) + "expected the number of atoms alone on the first line");
  if (lines.size() < 2) throw Error(at(2) + "missing the comment line (Lattice=, pbc=, Properties=)");
  const auto pairs = comment_pairs(lines[1], at(2));
  Structure structure;
  structure.points.dims = 3;
  if (const auto lattice = pairs.find("lattice"); lattice != pairs.end()) {
    const auto values = words(lattice->second);
    if (values.size() != 9)
      throw Error(at(2) + "key Lattice: expected 9 numbers (a, b, c), found " + std::to_string(values.size()));
    for (int k = 0; k < 9; ++k)
      if (!number(values[k], structure.cell.vectors[k / 3][k % 3]))
        throw Error(at(2) + "key Lattice: '" + values[k] + "' is not a finite number");
    structure.cell.pbc = {true, true, true};  // ASE's default with a lattice
  }
  if (const auto pbc = pairs.find("pbc"); pbc != pairs.end()) {
    const auto values = words(pbc->second);
    if (values.size() != 3) throw Error(at(2) + "key pbc: expected 3 flags such as \"T T F\", found '" + pbc->second + "'");
    for (int k = 0; k < 3; ++k)
      if (!flag(values[k], structure.cell.pbc[k]))
        throw Error(at(2) + "key pbc: '" + values[k] + "' is not T or F");
    if (structure.cell.periodic() && pairs.find("lattice") == pairs.end())
      throw Error(at(2) + "key pbc: periodic axes need a Lattice=\"...\"");
  }
  // Properties=name:type:columns:... ; the positions are the pos:R:3 column group.
  const auto properties = pairs.find("properties");
  const std::string spec = properties == pairs.end() ? "species:S:1:pos:R:3" : properties->second;
  std::size_t columns = 0, position_column = 0;
  bool found = false;
  std::vector<std::string> parts;
  for (std::size_t from = 0; from <= spec.size();) {
    const std::size_t colon = std::min(spec.find(':', from), spec.size());
    parts.push_back(spec.substr(from, colon - from));
    from = colon + 1;
  }
  if (parts.size() % 3 != 0) throw Error(at(2) + "key Properties: expected name:type:count triples, found '" + spec + "'");
  for (std::size_t p = 0; p < parts.size(); p += 3) {
    long long width = 0;
    if (!integer(parts[p + 2], width) || width < 1)
      throw Error(at(2) + "key Properties: '" + parts[p + 2] + "' (of " + parts[p] + ") is not a column count");
    if (parts[p] == "pos") {
      if (parts[p + 1] != "R" || width != 3) throw Error(at(2) + "key Properties: pos must be R:3, found " + parts[p + 1] + ":" + parts[p + 2]);
      position_column = columns;
      found = true;
    }
    columns += static_cast<std::size_t>(width);
  }
  if (!found) throw Error(at(2) + "key Properties: no pos:R:3 column in '" + spec + "'");
  const auto atoms = static_cast<std::size_t>(count);
  if (lines.size() < 2 + atoms)
    throw Error(path + ": the first line declares " + std::to_string(atoms) + " atoms but " +
                std::to_string(lines.size() - 2) + " atom lines follow");
  for (std::size_t n = 2 + atoms; n < lines.size(); ++n)
    if (!words(lines[n]).empty())
      throw Error(at(n + 1) + "a second frame (or extra text) after the " + std::to_string(atoms) +
                  " atoms: horizon reads files of one frame");
  structure.points.xyz.reserve(3 * atoms);
  for (std::size_t a = 0; a < atoms; ++a) {
    const auto fields = words(lines[2 + a]);
    if (fields.size() != columns)
      throw Error(at(3 + a) + "expected " + std::to_string(columns) + " columns (Properties=" + spec + "), found " +
                  std::to_string(fields.size()));
    for (int k = 0; k < 3; ++k) {
      double x = 0;
      if (!number(fields[position_column + k], x))
        throw Error(at(3 + a) + "position '" + fields[position_column + k] + "' is not a finite number");
      structure.points.xyz.push_back(x);
    }
  }
  return structure;
}

// ---- LAMMPS data ---------------------------------------------------------------------------

/// The columns of x, y, z in an Atoms line of each atom style (id first).
int position_column(const std::string& style) {
  if (style == "atomic") return 2;
  if (style == "charge" || style == "molecular" || style == "bond" || style == "angle") return 3;
  if (style == "full") return 4;
  return -1;
}

/// Section headers of a data file (the body's keywords).
bool is_section(const std::string& word) {
  static const char* sections[] = {"Atoms", "Velocities", "Masses", "Ellipsoids", "Lines", "Triangles", "Bodies",
                                   "Bonds", "Angles", "Dihedrals", "Impropers", "Pair", "PairIJ", "Bond", "Angle",
                                   "Dihedral", "Improper", "BondBond", "BondAngle", "MiddleBondTorsion",
                                   "EndBondTorsion", "AngleTorsion", "AngleAngleTorsion", "BondBond13", "AngleAngle"};
  return std::any_of(std::begin(sections), std::end(sections), [&](const char* s) { return word == s; });
}

Structure read_lammps_data(const std::string& path) {
  const std::vector<std::string> lines = lines_of(path);
  const auto at = [&](std::size_t line) { return path + ":" + std::to_string(line + 1) + ": "; };
  long long atoms = -1;
  double bounds[3][2] = {};
  bool bounded[3] = {false, false, false};
  double tilt[3] = {0, 0, 0};  // xy xz yz
  std::size_t line = 1;        // the first line is a comment
  // Header: "N atoms", "xlo xhi" and the like, up to the first section.
  for (; line < lines.size(); ++line) {
    std::string text = lines[line].substr(0, lines[line].find('#'));
    const auto fields = words(text);
    if (fields.empty()) continue;
    if (is_section(fields[0])) break;
    const std::string& last = fields.back();
    if (fields.size() == 2 && last == "atoms") {
      if (!integer(fields[0], atoms) || atoms < 0) throw Error(at(line) + "key atoms: '" + fields[0] + "' is not a count");
    } else if (fields.size() == 4 && (last == "xhi" || last == "yhi" || last == "zhi")) {
      const int axis = last[0] - 'x';
      if (!number(fields[0], bounds[axis][0]) || !number(fields[1], bounds[axis][1]))
        throw Error(at(line) + "key " + fields[2] + " " + last + ": expected two numbers");
      if (!(bounds[axis][1] > bounds[axis][0]))
        throw Error(at(line) + "key " + fields[2] + " " + last + ": the upper bound must exceed the lower");
      bounded[axis] = true;
    } else if (fields.size() == 6 && fields[3] == "xy" && fields[4] == "xz" && fields[5] == "yz") {
      for (int k = 0; k < 3; ++k)
        if (!number(fields[k], tilt[k])) throw Error(at(line) + "key xy xz yz: '" + fields[k] + "' is not a number");
    }
  }
  if (atoms < 0) throw Error(path + ": the header has no 'N atoms' line");
  for (int axis = 0; axis < 3; ++axis)
    if (!bounded[axis])
      throw Error(path + ": the header has no '" + std::string(1, "xyz"[axis]) + "lo " + "xyz"[axis] + "hi' line");
  // The Atoms section: "Atoms # style", a blank line, then one line per atom.
  while (line < lines.size() && words(lines[line].substr(0, lines[line].find('#'))) != std::vector<std::string>{"Atoms"})
    ++line;
  if (line == lines.size()) throw Error(path + ": no Atoms section");
  std::string style;
  if (const auto hash = lines[line].find('#'); hash != std::string::npos) {
    const auto named = words(lines[line].substr(hash + 1));
    if (!named.empty()) style = named[0];
  }
  int column = style.empty() ? -1 : position_column(style);
  if (!style.empty() && column < 0)
    throw Error(at(line) + "Atoms # " + style + ": horizon reads the atomic, charge, molecular, bond, angle and full styles");
  std::vector<std::pair<long long, std::array<double, 3>>> read;
  for (++line; line < lines.size() && read.size() < static_cast<std::size_t>(atoms); ++line) {
    const auto fields = words(lines[line].substr(0, lines[line].find('#')));
    if (fields.empty()) continue;
    if (is_section(fields[0])) break;
    if (column < 0) {  // no style named: atomic (5 columns, or 8 with image flags), else ambiguous
      if (fields.size() != 5 && fields.size() != 8)
        throw Error(at(line) + "Atoms: " + std::to_string(fields.size()) +
                    " columns; name the atom style after the section header (Atoms # full)");
      column = 2;
    }
    const auto needed = static_cast<std::size_t>(column + 3);
    if (fields.size() != needed && fields.size() != needed + 3)
      throw Error(at(line) + "Atoms # " + (style.empty() ? "atomic" : style) + ": expected " + std::to_string(needed) +
                  " columns (or " + std::to_string(needed + 3) + " with image flags), found " + std::to_string(fields.size()));
    long long id = 0;
    if (!integer(fields[0], id) || id < 1) throw Error(at(line) + "atom id '" + fields[0] + "' is not a positive integer");
    std::array<double, 3> x{};
    for (int k = 0; k < 3; ++k)
      if (!number(fields[column + k], x[k]))
        throw Error(at(line) + "atom " + fields[0] + ": coordinate '" + fields[column + k] + "' is not a finite number");
    read.emplace_back(id, x);
  }
  if (read.size() != static_cast<std::size_t>(atoms))
    throw Error(path + ": the header declares " + std::to_string(atoms) + " atoms but the Atoms section has " +
                std::to_string(read.size()));
  // Point k is the atom of the k-th smallest id (ids 1..N: point id - 1).
  std::sort(read.begin(), read.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t k = 1; k < read.size(); ++k)
    if (read[k].first == read[k - 1].first) throw Error(path + ": atom id " + std::to_string(read[k].first) + " appears twice");
  Structure structure;
  structure.points.dims = 3;
  for (const auto& [id, x] : read) structure.points.xyz.insert(structure.points.xyz.end(), x.begin(), x.end());
  // LAMMPS's restricted triclinic box: a = (lx, 0, 0), b = (xy, ly, 0), c = (xz, yz, lz).
  structure.cell.vectors = {{{bounds[0][1] - bounds[0][0], 0, 0},
                             {tilt[0], bounds[1][1] - bounds[1][0], 0},
                             {tilt[1], tilt[2], bounds[2][1] - bounds[2][0]}}};
  structure.cell.pbc = {true, true, true};  // the data file has no boundary; the input script's default is p p p
  return structure;
}

}  // namespace

bool is_structure_file(const std::string& path) {
  const std::string name = basename(path);
  if (name.ends_with(".extxyz") || name.ends_with(".data") || name.ends_with(".lmp") || name.rfind("data.", 0) == 0)
    return true;
  if (!name.ends_with(".xyz")) return false;
  // .xyz: extended XYZ when its first line is a count alone (plain text points have 2-3 columns).
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  const auto fields = words(first);
  long long count = 0;
  return fields.size() == 1 && integer(fields[0], count);
}

Structure read_structure(const std::string& path) {
  const std::string name = basename(path);
  if (name.ends_with(".xyz") || name.ends_with(".extxyz")) return read_extxyz(path);
  return read_lammps_data(path);
}

}  // namespace horizon
