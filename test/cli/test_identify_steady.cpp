// identify_steady's exact cache (doc/data/steady_exact_curves*.csv) is keyed by a/b, ray and e
// alone: a cache solved for another setup must stop the tool, not be read as this setup's curves.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "process.hpp"

TEST(IdentifySteady, RefusesAnExactCacheSolvedForAnotherSetup) {
  const std::string cache = testing::TempDir() + "identify_steady_nu028.csv";
  std::ofstream(cache)
      << "# Exact steady creep curves (our half-space solver, 20x20 elements over 1.1a x 1.1b, "
         "Hertz pressure; G 8.2e+10 Pa, nu 0.28, mu 0.3, fz 10000 N, sqrt(ab) 5 mm)\n"
         "a_over_b,ray,epsilon,xi,eta,phi,fx,fy,mz\n"
         "1,11,0.05,1.8e-05,0,0,-0.050762,0,0\n";
  const std::string before = wrc_test::fileText(cache);
  // Without the check the tool would go on to solve the rays' exact points for minutes: the
  // timeout turns that into a failure here.
  std::string out;
  const int code = wrc_test::run("timeout 120 " + std::string(WRC_IDENTIFY_STEADY) +
                                     " --nu 0.3 --nx 20 --ab 1 --exact " + cache,
                                 &out);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("was solved for another setup"), std::string::npos) << out;
  EXPECT_NE(out.find("nu 0.3,"), std::string::npos) << out;  // the setup asked for
  EXPECT_EQ(wrc_test::fileText(cache), before);              // the cache is left as it was
}
