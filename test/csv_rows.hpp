// Splits CSV text into rows of cells (tests only; no quoting).
#pragma once

#include <istream>
#include <sstream>
#include <string>
#include <vector>

inline std::vector<std::vector<std::string>> csvRows(std::istream& in) {
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}
