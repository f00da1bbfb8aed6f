#include "rownav/io/progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace rownav::io {
namespace {

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(Progress, PlainOutputOneLinePerTenPercent) {
  std::ostringstream out;
  {
    Progress p("simulate", 30.0, out);
    for (int i = 0; i <= 300; ++i) p.update(i * 0.1);
    p.finish();
    p.finish();  // idempotent
  }
  const auto l = lines(out.str());
  ASSERT_EQ(l.size(), 11u) << out.str();  // 0 %, 10 % ... 90 %, and the final 100 %
  EXPECT_EQ(l[0], "simulate: 0% 0.0/30.0");
  EXPECT_EQ(l[4], "simulate: 40% 12.0/30.0");
  EXPECT_EQ(l.back(), "simulate: 100% 30.0/30.0");
  EXPECT_EQ(out.str().find('\r'), std::string::npos);
}

TEST(Progress, PlainOutputSkipsNoStepAndFinishesInDestructor) {
  std::ostringstream out;
  {
    Progress p("eval", 10.0, out);
    p.update(5.5);   // jumps straight to 50 %
    p.update(5.6);   // same step: nothing
    p.update(-3.0);  // clamped, earlier step: nothing
  }
  const auto l = lines(out.str());
  ASSERT_EQ(l.size(), 2u) << out.str();
  EXPECT_EQ(l[0], "eval: 55% 5.5/10.0");
  EXPECT_EQ(l[1], "eval: 100% 10.0/10.0");
}

TEST(Progress, TtyRedrawsOneLineAtMostTenTimesASecond) {
  std::ostringstream out;
  Progress p("run", 30.0, out, true);
  for (int i = 0; i < 1000; ++i) p.update(i * 0.03);  // far faster than 10 Hz
  p.finish();
  const std::string s = out.str();
  const auto redraws = std::count(s.begin(), s.end(), '\r');
  EXPECT_GE(redraws, 2);  // first update and finish
  EXPECT_LE(redraws, 4);  // rate-limited (the loop takes well under 0.2 s)
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1);
  EXPECT_NE(s.find("\rrun [####################] 100% 30.0/30.0 ETA 0:00\n"), std::string::npos)
      << s;
  EXPECT_EQ(s.rfind("\rrun [....................] 0% 0.0/30.0 ETA --:--", 0), 0u) << s;
}

}  // namespace
}  // namespace rownav::io
