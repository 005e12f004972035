// runner::contact_marks and run_figure_legend: the run figure marks every contact of the run up to
// each panel's time, and names them in its legend.
#include "bipednav/runner/run_figure.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace bipednav;

namespace {

sim::CollisionEvent contact(double t_s, double x, double y) {
  sim::CollisionEvent e;
  e.time_s = t_s;
  e.point = {x, y};
  e.obstacle = "wall";
  return e;
}

runner::RunResult three_contacts() {
  runner::RunResult r;
  r.contacts = {contact(2.0, 1.0, 0.0), contact(5.0, 2.0, 1.0), contact(9.0, 3.0, -1.0)};
  r.first_collision = r.contacts.front();
  r.collisions = 3;
  return r;
}

bool has_entry(const std::vector<viz::LegendEntry>& legend, const std::string& label) {
  return std::any_of(legend.begin(), legend.end(), [&](const viz::LegendEntry& e) { return e.label == label; });
}

}  // namespace

TEST(RunFigure, MarksEveryContactUpToThePanelsTime) {
  const runner::RunResult r = three_contacts();
  const auto all = runner::contact_marks(r, 10.0);
  ASSERT_EQ(all.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(all[i], r.contacts[i].point);
  const auto two = runner::contact_marks(r, 5.0);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[1], r.contacts[1].point);
  EXPECT_TRUE(runner::contact_marks(r, 1.0).empty());
}

TEST(RunFigure, RunWithoutContactListMarksItsFirstCollision) {
  runner::RunResult r;
  EXPECT_TRUE(runner::contact_marks(r, 100.0).empty());
  r.first_collision = contact(3.0, -1.0, 2.0);
  r.collisions = 1;
  const auto marks = runner::contact_marks(r, 100.0);
  ASSERT_EQ(marks.size(), 1u);
  EXPECT_EQ(marks[0], Eigen::Vector2d(-1.0, 2.0));
}

TEST(RunFigure, LegendNamesTheContacts) {
  sim::Scenario s;
  runner::RunResult r;
  EXPECT_FALSE(has_entry(runner::run_figure_legend(s, r, "teb"), "contact"));
  r.first_collision = contact(1.0, 0.0, 0.0);
  r.contacts = {*r.first_collision};
  r.collisions = 1;
  EXPECT_TRUE(has_entry(runner::run_figure_legend(s, r, "teb"), "contact"));
  EXPECT_TRUE(has_entry(runner::run_figure_legend(s, three_contacts(), "teb"), "contacts (3)"));
}
