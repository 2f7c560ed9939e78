// SPDX-License-Identifier: BSD-3-Clause
// The text tokenizer of the scene formats (SceneFile.h): the one copy the PLY header, the
// ASCII PLY body and the COLMAP text files read their words and numbered lines with.
#include "GaussianIO.h"
#include "SceneFile.h"

#include <gtest/gtest.h>

#include <dirent.h>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <sys/stat.h>
#include <vector>

namespace vis4gs
{

TEST(SceneFile, SplitWordsOnSpacesTabsAndCarriageReturns)
{
  using detail::SplitWords;
  const std::vector<std::string_view> words = SplitWords("  property\tfloat  x\r");
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0], "property");
  EXPECT_EQ(words[1], "float");
  EXPECT_EQ(words[2], "x");
  EXPECT_TRUE(SplitWords("").empty());
  EXPECT_TRUE(SplitWords(" \t\r ").empty());
  // Other bytes, '#' and non-ASCII included, belong to words.
  const auto other = SplitWords("#\xc3\xa9 a,b\v");
  ASSERT_EQ(other.size(), 2u);
  EXPECT_EQ(other[0], "#\xc3\xa9");
  EXPECT_EQ(other[1], "a,b\v");
}

TEST(SceneFile, TextLinesNumbersAndSkipsLines)
{
  const std::string text = "# camera list\n\n1 PINHOLE 4 3\r\n  \t\n  # indented comment\nlast";
  std::string_view line;
  detail::TextLines words(text);
  ASSERT_TRUE(words.Next(line));
  EXPECT_EQ(line, "# camera list");
  EXPECT_EQ(words.LineNumber(), 1u);
  ASSERT_TRUE(words.Next(line));
  EXPECT_EQ(line, "1 PINHOLE 4 3\r");
  EXPECT_EQ(words.LineNumber(), 3u);

  detail::TextLines data(text);
  ASSERT_TRUE(data.Next(line, true));
  EXPECT_EQ(line, "1 PINHOLE 4 3\r");
  EXPECT_EQ(data.LineNumber(), 3u);
  ASSERT_TRUE(data.Next(line, true)); // the last line needs no newline
  EXPECT_EQ(line, "last");
  EXPECT_EQ(data.LineNumber(), 6u);
  EXPECT_FALSE(data.Next(line, true));

  // Raw returns blank lines too; a start offset continues the numbering of what precedes.
  detail::TextLines raw(text, text.find("\n\n") + 1, 1);
  ASSERT_TRUE(raw.Raw(line));
  EXPECT_EQ(line, "");
  EXPECT_EQ(raw.LineNumber(), 2u);
  ASSERT_TRUE(raw.Raw(line));
  EXPECT_EQ(raw.LineNumber(), 3u);
  detail::TextLines empty("");
  EXPECT_FALSE(empty.Raw(line));
  EXPECT_EQ(empty.LineNumber(), 0u);
}

//------------------------------------------------------------------------------
// WriteTextFile (GaussianIO.h), the tables and reports of the commands: it replaces a file
// whole, and a failure names the path and the problem and leaves no temporary and the old
// file as it was (full disks and read-only folders: Applications/vis4gs/Testing/CheckFullDisk.py).
namespace
{
std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> Entries(const std::string& folder)
{
  std::vector<std::string> names;
  if (DIR* dir = ::opendir(folder.c_str()))
  {
    while (const dirent* e = ::readdir(dir))
    {
      const std::string name = e->d_name;
      if (name != "." && name != "..")
      {
        names.push_back(name);
      }
    }
    ::closedir(dir);
  }
  return names;
}
}

TEST(SceneFile, WriteTextFileReplacesWholeAndFailsNamingThePath)
{
  const std::string folder = ::testing::TempDir() + "vis4gs-write-text-file";
  ::mkdir(folder.c_str(), 0755);
  const std::string path = folder + "/table.csv";
  WriteTextFile(path, "a,b\n1,2\n");
  WriteTextFile(path, "a\n3\n");
  EXPECT_EQ(Slurp(path), "a\n3\n");
  EXPECT_EQ(Entries(folder), std::vector<std::string>{ "table.csv" }); // no temporary left
  const std::string missing = folder + "/no-such-folder/table.csv";
  try
  {
    WriteTextFile(missing, "x\n");
    ADD_FAILURE() << "a file in a missing folder was written";
  }
  catch (const std::runtime_error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find(missing), std::string::npos) << what;
    EXPECT_NE(what.find("No such file or directory"), std::string::npos) << what;
  }
  EXPECT_EQ(Slurp(path), "a\n3\n");
  EXPECT_EQ(Entries(folder), std::vector<std::string>{ "table.csv" });
}

} // namespace vis4gs
