// identify_steady's exact cache (doc/data/steady_exact_curves*.csv) is keyed by a/b, ray and e
// alone: a cache solved for another setup must stop the tool, not be read as this setup's curves.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(IdentifySteady, RefusesAnExactCacheSolvedForAnotherSetup) {
  const std::string cache = testing::TempDir() + "identify_steady_nu028.csv";
  std::ofstream(cache)
      << "# Exact steady creep curves (our half-space solver, 20x20 elements over 1.1a x 1.1b, "
         "Hertz pressure; G 8.2e+10 Pa, nu 0.28, mu 0.3, fz 10000 N, sqrt(ab) 5 mm)\n"
         "a_over_b,ray,epsilon,xi,eta,phi,fx,fy,mz\n"
         "1,11,0.05,1.8e-05,0,0,-0.050762,0,0\n";
  const std::string before = readAll(cache);
  // Without the check the tool would go on to solve the rays' exact points for minutes: the
  // timeout turns that into a failure here.
  const std::string cmd = "timeout 120 " + std::string(WRC_IDENTIFY_STEADY) +
                          " --nu 0.3 --nx 20 --ab 1 --exact " + cache + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 1) << out;
  EXPECT_NE(out.find("was solved for another setup"), std::string::npos) << out;
  EXPECT_NE(out.find("nu 0.3,"), std::string::npos) << out;  // the setup asked for
  EXPECT_EQ(readAll(cache), before);                         // the cache is left as it was
}
