// SPDX-License-Identifier: BSD-3-Clause
// The score registry (ScoreRegistry.h): names that every interface can use (unique, the
// rule language's identifiers), list parsing and its errors, and that each entry's
// computation is what it says: its request switch alone fills its values member alone, with
// what its Needs bits say it needs.
#include "ScoreRegistry.h"

#include "Rasterizer.h"

#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <stdexcept>
#include <string>

namespace
{
using vis4gs::ScoreDefinition;
using vis4gs::ScoreDefinitions;
} // namespace

TEST(ScoreRegistry, NamesAreUniqueAndUsable)
{
  std::set<std::string> names, arrays, rules;
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    EXPECT_TRUE(names.insert(d.Name).second) << d.Name;
    EXPECT_TRUE(arrays.insert(d.ArrayName).second) << d.ArrayName;
    EXPECT_TRUE(rules.insert(d.RuleName).second) << d.RuleName;
    // Short names are kebab-case (a command-line list), rule names identifiers.
    for (const char* c = d.Name; *c; ++c)
    {
      EXPECT_TRUE(std::islower(*c) || *c == '-') << d.Name;
    }
    for (const char* c = d.RuleName; *c; ++c)
    {
      EXPECT_TRUE(std::islower(*c) || *c == '_') << d.RuleName;
    }
    EXPECT_NE(d.Suspicious, vis4gs::SuspiciousEnd::None) << d.Name;
    EXPECT_EQ(vis4gs::SuspiciousEndOf(d.ArrayName), d.Suspicious);
    EXPECT_EQ(vis4gs::FindScore(d.Name), &d);
    EXPECT_EQ(vis4gs::FindScore(d.ArrayName), &d);
    EXPECT_TRUE(d.Request != nullptr && d.Values != nullptr) << d.Name;
    EXPECT_GT(std::string(d.Doc).size(), 20u) << d.Name;
  }
  // A short name is never another score's array name.
  for (const std::string& n : names)
  {
    EXPECT_EQ(arrays.count(n), 0u) << n;
  }
  EXPECT_EQ(vis4gs::SuspiciousEndOf("Opacity"), vis4gs::SuspiciousEnd::None);
  EXPECT_EQ(vis4gs::FindScore("Opacity"), nullptr);
}

TEST(ScoreRegistry, DefaultsAreTheDefaultRequest)
{
  const vis4gs::ScoreRequest request;
  std::string expected;
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    EXPECT_EQ(d.DefaultOn, request.*(d.Request)) << d.Name;
    if (d.DefaultOn)
    {
      expected += (expected.empty() ? "" : ",") + std::string(d.Name);
    }
  }
  EXPECT_EQ(vis4gs::DefaultScoreList(), expected);
}

TEST(ScoreRegistry, ParseScoreList)
{
  const auto all = vis4gs::ParseScoreList(vis4gs::ScoreNames(","));
  ASSERT_EQ(all.size(), ScoreDefinitions().size());
  // Registry order whatever the list's order; duplicates and blanks ignored.
  const auto some = vis4gs::ParseScoreList(" shape , coverage,,shape");
  ASSERT_EQ(some.size(), 2u);
  EXPECT_EQ(std::string(some[0]->Name), "coverage");
  EXPECT_EQ(std::string(some[1]->Name), "shape");
  EXPECT_TRUE(vis4gs::ParseScoreList("").empty());
  try
  {
    vis4gs::ParseScoreList("coverage,bluur");
    FAIL() << "an unknown score was accepted";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("'bluur'"), std::string::npos) << what;
    EXPECT_NE(what.find("render-cost"), std::string::npos) << what;
  }
  // Array names are not short names in a list.
  EXPECT_THROW(vis4gs::ParseScoreList("ViewCoverage"), std::invalid_argument);
}

TEST(ScoreRegistry, EachRequestFillsItsOwnValues)
{
  vis4gs::GaussianCloud cloud;
  cloud.Resize(4, 0);
  for (std::size_t i = 0; i < cloud.Count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      cloud.Positions[3 * i + k] = k == 2 ? 5.0f : 0.2f * static_cast<float>(i) - 0.3f;
      cloud.LogScales[3 * i + k] = -2.0f - 0.5f * static_cast<float>(k);
    }
    cloud.Rotations[4 * i] = 1;
    cloud.OpacityLogits[i] = 1;
  }
  vis4gs::Camera camera;
  camera.Name = "view";
  camera.Width = 32;
  camera.Height = 24;
  camera.Fx = camera.Fy = 40;
  camera.Cx = 16;
  camera.Cy = 12;
  camera.WorldToCamera = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  int imagesRead = 0;
  auto images = [&](std::size_t, const vis4gs::Camera& c, vis4gs::Image& image)
  {
    ++imagesRead;
    image.Width = c.Width;
    image.Height = c.Height;
    image.Channels = 3;
    image.Pixels.assign(3 * static_cast<std::size_t>(c.Width) * c.Height, 0.25f);
    return true;
  };
  for (const ScoreDefinition& d : ScoreDefinitions())
  {
    vis4gs::ScoreSettings settings;
    settings.Request = vis4gs::ScoreRequest{ false, false, false, false, false, false };
    settings.Request.*(d.Request) = true;
    EXPECT_EQ(vis4gs::NeedsOf(settings.Request), d.Needs) << d.Name;
    imagesRead = 0;
    const std::vector<vis4gs::Camera> cameras = { camera };
    const auto scores = vis4gs::ComputeGaussianScores(cloud,
      (d.Needs & vis4gs::NeedsCameras) ? cameras : std::vector<vis4gs::Camera>(),
      settings,
      (d.Needs & vis4gs::NeedsImages) ? vis4gs::TrainingImageProvider(images)
                                      : vis4gs::TrainingImageProvider());
    EXPECT_EQ(imagesRead > 0, (d.Needs & vis4gs::NeedsImages) != 0) << d.Name;
    for (const ScoreDefinition& other : ScoreDefinitions())
    {
      EXPECT_EQ((scores.*(other.Values)).size(), &other == &d ? cloud.Count : 0u)
        << d.Name << " asked, " << other.Name << " filled";
    }
  }
}
