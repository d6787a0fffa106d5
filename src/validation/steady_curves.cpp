#include "validation/steady_curves.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace wheel_rail_contact {

std::vector<SteadyCurvePoint> readSteadyCurves(const std::string& path) {
  std::vector<SteadyCurvePoint> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("a_over_b", 0) == 0) continue;
    std::stringstream ss(line);
    std::vector<std::string> f;
    for (std::string s; std::getline(ss, s, ',');) f.push_back(s);
    if (f.size() < 9) throw std::runtime_error(path + ": short line: " + line);
    try {
      out.push_back({std::stod(f[0]), f[1], std::stod(f[2]),
                     Creepages{std::stod(f[3]), std::stod(f[4]), std::stod(f[5])}, std::stod(f[6]),
                     std::stod(f[7]), std::stod(f[8])});
    } catch (const std::logic_error&) {  // stod: invalid_argument or out_of_range
      throw std::runtime_error(path + ": not a number in: " + line);
    }
  }
  return out;
}

}  // namespace wheel_rail_contact
