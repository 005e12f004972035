#include "bipednav/io/param_reader.hpp"

#include <gtest/gtest.h>

using bipednav::FileError;
using bipednav::io::ParamReader;

TEST(ParamReader, ReadsPresentKeysAndKeepsDefaults) {
  auto r = ParamReader::from_string("a: 2.5\nname: digit\nnested: {k: 3}\n", "t.yaml");
  double a = 1.0, b = 7.0;
  std::string name;
  int k = 0;
  EXPECT_TRUE(r.get("a", a));
  EXPECT_FALSE(r.get("b", b));
  r.get("name", name);
  r.child("nested").get("k", k);
  r.finish();
  EXPECT_DOUBLE_EQ(a, 2.5);
  EXPECT_DOUBLE_EQ(b, 7.0);
  EXPECT_EQ(name, "digit");
  EXPECT_EQ(k, 3);
}

TEST(ParamReader, WrongTypeNamesFileLineAndField) {
  auto r = ParamReader::from_string("x: 1\nmax_vel_x_mps: fast\n", "robot.yaml");
  double v = 0;
  try {
    r.get("max_vel_x_mps", v);
    FAIL();
  } catch (const FileError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("robot.yaml"), std::string::npos);
    EXPECT_NE(msg.find("line 2"), std::string::npos);
    EXPECT_NE(msg.find("max_vel_x_mps"), std::string::npos);
    EXPECT_NE(msg.find("number"), std::string::npos);
  }
}

TEST(ParamReader, UnknownKeyAndMalformedYamlAreRejected) {
  auto r = ParamReader::from_string("typo_key: 1\n", "p.yaml");
  EXPECT_THROW(r.finish(), FileError);
  EXPECT_THROW(ParamReader::from_string("a: [1, 2\n", "bad.yaml"), FileError);
  EXPECT_THROW(ParamReader::from_file("/nonexistent/file.yaml"), FileError);
  EXPECT_THROW(ParamReader::from_string("- 1\n- 2\n", "list.yaml"), FileError);
}

// Found by fuzz/fuzz_param_yaml: a list or mapping used as a key escaped as a yaml-cpp exception.
TEST(ParamReader, NonScalarKeysAreRejectedWithTheFileAndLine) {
  for (const char* yaml : {"a: 1\n? [x, y]\n: 2\n", "? {k: v}\n: 2\n"}) {
    auto r = ParamReader::from_string(yaml, "keys.yaml");
    double a = 0.0;
    r.get("a", a);
    try {
      r.finish();
      ADD_FAILURE() << "no FileError for " << yaml;
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find("keys.yaml:line "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("a list or mapping as a key"), std::string::npos) << e.what();
    }
  }
  auto nested = ParamReader::from_string("outer:\n  ? [1]\n  : 2\n", "keys.yaml").child("outer");
  EXPECT_THROW(nested.finish(), FileError);
  auto null_key = ParamReader::from_string("~: 1\n", "keys.yaml");
  EXPECT_THROW(null_key.finish(), FileError);
}
