// Profile files: Simpack's rail-wheel profile format and plain two-column text or CSV.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/profiles/profile_impl.hpp"
#include "core/profiles/standard_profiles.hpp"
#include "wheel_rail_contact/profiles/profile.hpp"

namespace wheel_rail_contact {

namespace {

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// The whole token as a double (finite or not: the caller says which it accepts).
bool parseNumber(const std::string& token, double* out) {
  if (token.empty()) return false;
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end != begin + token.size()) return false;
  *out = v;
  return true;
}

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',' || c == ';' || std::isspace(static_cast<unsigned char>(c))) {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

/// Reads "lateral vertical [weight]" into *p (file units); a message on failure.
std::string parsePointLine(const std::string& line, ProfileSourcePoint* p) {
  const std::vector<std::string> f = splitFields(line);
  if (f.size() < 2 || f.size() > 3)
    return "expected 2 or 3 numbers (lateral, vertical[, weight]), found " +
           std::to_string(f.size()) + " fields";
  double v[3] = {0.0, 0.0, 1.0};
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!parseNumber(f[i], &v[i])) return "'" + f[i] + "' is not a number";
    if (!std::isfinite(v[i])) return "'" + f[i] + "' is not a finite number";
  }
  if (!(v[2] > 0.0)) return "the weight " + f[2] + " is not positive";
  p->p = Eigen::Vector2d(v[0], v[1]);
  p->weight = v[2];
  return {};
}

/// Metres per unit for a unit's name, 0 if unknown.
double unitFactor(const std::string& u) {
  if (u == "mm") return 1e-3;
  if (u == "m") return 1.0;
  return 0.0;
}

struct Parsed {
  std::vector<ProfileSourcePoint> points;  // file units, file axes
  double unit = 0.0;                       // metres per file unit, 0 if the file says nothing
  int unit_line = 0;
};

// ---- Simpack ----------------------------------------------------------------------------------

/// The text before a '!' outside quotes.
std::string stripSimpackComment(const std::string& line) {
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '\'') quoted = !quoted;
    if (line[i] == '!' && !quoted) return line.substr(0, i);
  }
  return line;
}

Parsed parseSimpack(const std::vector<std::string>& lines, const std::string& name,
                    ProfileKind kind) {
  enum class Block { kNone, kHeader, kSpline, kPoints };
  Block block = Block::kNone;
  std::map<std::string, std::pair<double, int>> header, spline;
  std::vector<ProfileSourcePoint> raw;
  bool seen_points = false, closed_points = false;
  int point_begin_line = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int ln = static_cast<int>(i) + 1;
    const std::string text = trim(stripSimpackComment(lines[i]));
    if (text.empty()) continue;
    const std::string key = lower(text);
    if (key == "header.begin") {
      block = Block::kHeader;
    } else if (key == "header.end" || key == "spline.end") {
      block = Block::kNone;
    } else if (key == "spline.begin") {
      block = Block::kSpline;
    } else if (key == "point.begin") {
      if (block != Block::kSpline) refuse(name, ln, "point.begin outside spline.begin/spline.end");
      if (seen_points) refuse(name, ln, "a second point.begin block");
      block = Block::kPoints;
      seen_points = true;
      point_begin_line = ln;
    } else if (key == "point.end") {
      if (block != Block::kPoints) refuse(name, ln, "point.end without point.begin");
      block = Block::kSpline;
      closed_points = true;
    } else if (block == Block::kPoints) {
      ProfileSourcePoint p;
      p.line = ln;
      const std::string err = parsePointLine(text, &p);
      if (!err.empty()) refuse(name, ln, err);
      raw.push_back(p);
    } else if (block == Block::kHeader || block == Block::kSpline) {
      const std::size_t eq = text.find('=');
      if (eq == std::string::npos) refuse(name, ln, "expected 'key = value', found '" + text + "'");
      const std::string k = lower(trim(text.substr(0, eq)));
      const std::string value = trim(text.substr(eq + 1));
      if (!value.empty() && value.front() == '\'') continue;  // strings: file, comment
      double v = 0.0;
      if (!parseNumber(value, &v) || !std::isfinite(v))
        refuse(name, ln, "the value of " + k + " ('" + value + "') is not a finite number");
      (block == Block::kHeader ? header : spline)[k] = {v, ln};
    } else {
      refuse(name, ln, "'" + text + "' outside the header and spline blocks");
    }
  }
  if (!seen_points) refuse(name, 0, "no point.begin ... point.end block");
  if (!closed_points) refuse(name, point_begin_line, "point.begin without point.end");

  auto get = [&](const std::map<std::string, std::pair<double, int>>& m, const std::string& k,
                 double dflt, int* line = nullptr) {
    const auto it = m.find(k);
    if (line) *line = it == m.end() ? 0 : it->second.second;
    return it == m.end() ? dflt : it->second.first;
  };
  int ln = 0;
  const double type = get(header, "type", -1.0, &ln);
  if (type != -1.0) {
    if (type != 0.0 && type != 1.0) refuse(name, ln, "header type must be 0 (rail) or 1 (wheel)");
    const bool wheel = type == 1.0;
    if (wheel != (kind == ProfileKind::kWheel))
      refuse(name, ln,
             std::string("the file is a ") + (wheel ? "wheel" : "rail") + " profile, a " +
                 (kind == ProfileKind::kWheel ? "wheel" : "rail") + " profile was asked for");
  }
  auto flag = [&](const char* k) {
    int l = 0;
    const double v = get(spline, k, 0.0, &l);
    if (v != 0.0 && v != 1.0) refuse(name, l, std::string(k) + " must be 0 or 1");
    return v == 1.0;
  };
  // Simpack's processing steps in the order the file's own comments number them (1 to 7).
  const double dist_min = get(spline, "point.dist.min", 0.0, &ln);
  if (dist_min < 0.0) refuse(name, ln, "point.dist.min must be >= 0");
  std::vector<ProfileSourcePoint> pts;
  for (const auto& p : raw)  // 1: drop points closer than point.dist.min to the last one kept
    if (pts.empty() || dist_min <= 0.0 || (p.p - pts.back().p).norm() >= dist_min) pts.push_back(p);
  const Eigen::Vector2d shift(get(spline, "shift.y", 0.0), get(spline, "shift.z", 0.0));
  const double ang_f = get(spline, "units.ang.f", 1.0, &ln);
  if (!(ang_f > 0.0)) refuse(name, ln, "units.ang.f must be > 0");
  const double rot = get(spline, "rotate", 0.0) / ang_f;
  const double c = std::cos(rot), s = std::sin(rot);
  const double ylo = get(spline, "bound.y.min", 1.0), yhi = get(spline, "bound.y.max", 0.0);
  const double zlo = get(spline, "bound.z.min", 1.0), zhi = get(spline, "bound.z.max", 0.0);
  const bool mirror_y = flag("mirror.y"), mirror_z = flag("mirror.z");
  flag("inversion");  // the order is ours to choose (toward the track centre): checked only
  std::vector<ProfileSourcePoint> out;
  for (auto p : pts) {
    p.p += shift;                                                                 // 2
    p.p = Eigen::Vector2d(c * p.p.x() - s * p.p.y(), s * p.p.x() + c * p.p.y());  // 3, about +x
    if (ylo < yhi && (p.p.x() < ylo || p.p.x() > yhi)) continue;                  // 4
    if (zlo < zhi && (p.p.y() < zlo || p.p.y() > zhi)) continue;
    if (mirror_y) p.p.x() = -p.p.x();  // 5
    if (mirror_z) p.p.y() = -p.p.y();
    out.push_back(p);
  }
  Parsed r;
  r.points = std::move(out);
  const double len_f = get(spline, "units.len.f", 0.0, &ln);  // 7: file units per metre
  if (ln > 0) {
    if (!(len_f > 0.0)) refuse(name, ln, "units.len.f must be > 0");
    r.unit = 1.0 / len_f;
    r.unit_line = ln;
  }
  return r;
}

// ---- plain text / CSV -------------------------------------------------------------------------

bool isComment(const std::string& t) {
  return !t.empty() && (t[0] == '#' || t[0] == '%' || t[0] == '!');
}

/// A unit named in a comment line ("# unit: mm", "% units = m"): its factor, 0 if none, -1 if a
/// unit is named but unknown.
double unitFromComment(const std::string& t) {
  std::string s = lower(trim(t.substr(1)));
  if (s.rfind("units", 0) == 0)
    s = s.substr(5);
  else if (s.rfind("unit", 0) == 0)
    s = s.substr(4);
  else
    return 0.0;
  s = trim(s);
  if (s.empty() || (s[0] != ':' && s[0] != '=')) return 0.0;
  const double f = unitFactor(trim(s.substr(1)));
  return f > 0.0 ? f : -1.0;
}

/// A unit named by a header's column names (y_mm, "y [mm]", z(m)): its factor, 0 if none, -1 if
/// the columns disagree.
double unitFromHeader(const std::vector<std::string>& cols) {
  double found = 0.0;
  for (const std::string& c0 : cols) {
    const std::string c = lower(c0);
    double f = 0.0;
    for (const char* u : {"mm", "m"}) {
      const std::string us(u);
      const bool suffix = c.size() > us.size() + 1 &&
                          c.compare(c.size() - us.size(), us.size(), us) == 0 &&
                          c[c.size() - us.size() - 1] == '_';
      if (suffix || c.find("[" + us + "]") != std::string::npos ||
          c.find("(" + us + ")") != std::string::npos) {
        f = unitFactor(us);
        break;
      }
    }
    if (f == 0.0) continue;
    if (found != 0.0 && found != f) return -1.0;
    found = f;
  }
  return found;
}

Parsed parseText(const std::vector<std::string>& lines, const std::string& name) {
  Parsed r;
  bool header_seen = false;
  // A unit named on line ln (a comment's or the header's): u > 0 the unit, 0 none, < 0 refused.
  auto takeUnit = [&](double u, int ln, const char* unknown) {
    if (u < 0.0) refuse(name, ln, unknown);
    if (u > 0.0) {
      if (r.unit > 0.0 && r.unit != u) refuse(name, ln, "a second, different unit");
      r.unit = u;
      r.unit_line = ln;
    }
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int ln = static_cast<int>(i) + 1;
    const std::string t = trim(lines[i]);
    if (t.empty()) continue;
    if (isComment(t)) {
      takeUnit(unitFromComment(t), ln, "unknown unit (mm or m)");
      continue;
    }
    ProfileSourcePoint p;
    p.line = ln;
    const std::string err = parsePointLine(t, &p);
    if (err.empty()) {
      r.points.push_back(p);
      continue;
    }
    const std::vector<std::string> f = splitFields(t);
    double dummy = 0.0;
    const bool numeric_start = !f.empty() && parseNumber(f[0], &dummy);
    if (r.points.empty() && !header_seen && !numeric_start) {  // a header of column names
      header_seen = true;
      takeUnit(unitFromHeader(f), ln, "the columns name different units");
      continue;
    }
    refuse(name, ln, err);
  }
  return r;
}

bool looksLikeSimpack(const std::vector<std::string>& lines) {
  for (const std::string& l : lines) {
    const std::string t = lower(trim(stripSimpackComment(l)));
    if (t == "header.begin" || t == "spline.begin") return true;
  }
  return false;
}

}  // namespace

Profile Profile::parse(const std::string& text, const std::string& name, ProfileKind kind,
                       const ProfileReadOptions& options) {
  if (!(options.length_unit >= 0.0) || !std::isfinite(options.length_unit))
    throw std::invalid_argument(
        "length_unit must be finite and >= 0 (m per file unit; 0: the file says)");
  std::vector<std::string> lines;
  {
    std::istringstream is(text);
    std::string l;
    while (std::getline(is, l)) {
      if (!l.empty() && l.back() == '\r') l.pop_back();
      lines.push_back(l);
    }
  }
  const Parsed parsed =
      looksLikeSimpack(lines) ? parseSimpack(lines, name, kind) : parseText(lines, name);
  double unit = options.length_unit;
  if (parsed.unit > 0.0) {
    if (unit > 0.0 && std::abs(unit - parsed.unit) > 1e-12 * unit)
      refuse(
          name, parsed.unit_line,
          "the file's unit disagrees with the length_unit given (" + std::to_string(unit) + " m)");
    unit = parsed.unit;
  }
  if (!(unit > 0.0))
    refuse(name, 0,
           "no length unit: give length_unit, or state it in the file (\"# unit: mm\", a header "
           "y_mm,z_mm, or Simpack's units.len.f)");
  const double sy = options.lateral == LateralAxis::kTowardGauge ? 1.0 : -1.0;
  const double sz = options.vertical == VerticalAxis::kUp ? 1.0 : -1.0;
  std::vector<ProfileSourcePoint> pts = parsed.points;
  for (auto& p : pts) p.p = Eigen::Vector2d(sy * unit * p.p.x(), sz * unit * p.p.y());
  return ProfileBuilder::build(std::move(pts), kind, name, options.smoothing_length,
                               options.min_point_distance, options.max_point_distance, sy, sz);
}

Profile Profile::read(const std::string& path, ProfileKind kind,
                      const ProfileReadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(path, 0, "cannot open the file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path, kind, options);
}

std::shared_ptr<const Profile> Profile::standardWheel() {
  static const std::shared_ptr<const Profile> p =
      std::make_shared<const Profile>(parse(std::string(standardWheelProfileText()),
                                            "MBench_S1002_v3.prw (built in)", ProfileKind::kWheel));
  return p;
}

std::shared_ptr<const Profile> Profile::standardRail() {
  static const std::shared_ptr<const Profile> p =
      std::make_shared<const Profile>(parse(std::string(standardRailProfileText()),
                                            "MBench_UIC60_v3.prr (built in)", ProfileKind::kRail));
  return p;
}

}  // namespace wheel_rail_contact
