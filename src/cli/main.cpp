// contact_cli: the offline front end of the wheel_rail_contact core (see cli.cpp).
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"

int main(int argc, char** argv) {
  return wheel_rail_contact::runCli(std::vector<std::string>(argv + 1, argv + argc), std::cout,
                                    std::cerr);
}
