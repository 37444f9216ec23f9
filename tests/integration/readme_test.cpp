// The front door stays true: README.md is at most 150 lines and the demo's
// output it quotes is what the demo's run prints; docs/README.md maps every
// doc, and no doc is over 400 lines.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/launch.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

const fs::path kRoot = LAGRANGE_SOURCE_DIR;

TEST(Readme, IsShortAndQuotesWhatTheDemoPrints) {
  const std::vector<std::string> readme = linesOf(readFile(kRoot / "README.md"));
  EXPECT_LE(readme.size(), 150u);
  // The fenced block after the marker: the demo's output, as quoted.
  std::vector<std::string> quoted;
  bool after_marker = false, in_block = false;
  for (const std::string& line : readme) {
    if (line.rfind("<!-- demo output", 0) == 0) after_marker = true;
    if (!after_marker) continue;
    if (line.rfind("```", 0) == 0) {
      if (in_block) break;
      in_block = true;
      continue;
    }
    if (in_block && !line.empty()) quoted.push_back(line);
  }
  ASSERT_GE(quoted.size(), 4u) << "no demo output quoted after the marker";
  // The demo's run (scripts/demo.sh's last line), from a folder with the repository's configs.
  const std::string work = freshDir("readme-demo");
  fs::create_directories(work);
  fs::create_directory_symlink(kRoot / "configs", fs::path(work) / "configs");
  const RunResult demo = shell("cd " + quote(work) + " && " + kBin +
                               "/lagrange run configs/rigid_2dof.yaml --out runs/rigid_2dof --report");
  ASSERT_EQ(demo.exit_code, 0) << demo.output;
  for (const std::string& line : quoted) EXPECT_NE(demo.output.find(line), std::string::npos) << line;
  // ... and the demo runs that command.
  EXPECT_NE(readFile(kRoot / "scripts/demo.sh")
                .find("lagrange run configs/rigid_2dof.yaml --out \"$out\" --report"),
            std::string::npos);
  fs::remove_all(work);
}

TEST(Readme, TheDocsMapNamesEveryDocAndNoDocIsOver400Lines) {
  const std::string map = readFile(kRoot / "docs/README.md");
  int docs = 0;
  for (const auto& entry : fs::directory_iterator(kRoot / "docs")) {
    if (entry.path().extension() != ".md") continue;
    ++docs;
    const std::string name = entry.path().filename().string();
    EXPECT_LE(linesOf(readFile(entry.path())).size(), 400u) << name;
    const bool mapped = name == "README.md" || map.find("(" + name) != std::string::npos;
    EXPECT_TRUE(mapped) << name << " is not on the map";
  }
  EXPECT_GE(docs, 20);
}

// The paper is cited where a reader starts (#54 item 5), and its equations and
// theorems are named as it prints them: the LaTeX source's labels ("eq. (11)",
// "(lego)", "eq. 830") and the project's old "Theorem 1..3" appear only where
// the two are mapped (citing.md, paper_in_code.md's table).
TEST(Readme, ThePaperIsCitedAndItsNumbersAreThePrintedOnes) {
  for (const char* doc : {"README.md", "docs/paper_in_code.md", "docs/citing.md"}) {
    const std::string text = readFile(kRoot / doc);
    EXPECT_NE(text.find("arXiv:1307.4659"), std::string::npos) << doc;
    EXPECT_NE(text.find("Observer-less output feedback global tracking control"), std::string::npos) << doc;
  }
  const std::string table = readFile(kRoot / "docs/paper_in_code.md");
  for (const char* row :
       {"| `11` | (12) |", "| `lego` | (74) |", "| `786` | (75) |", "| `830`, `830a`, `830c` |"})
    EXPECT_NE(table.find(row), std::string::npos) << row;
  const std::vector<std::string> labels = {
      "eq. (11)", "eq. 11",  "(lego)",     "eq. (632",   "eq. 632",    "(786)",      "eq. 830",
      "(830)",    "eq. 750", "Theorem 1 ", "Theorem 2 ", "Theorem 3 ", "Theorem 1'", "Theorem 3'"};
  std::vector<fs::path> read{kRoot / "README.md"};
  for (const auto& entry : fs::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") read.push_back(entry.path());
  for (const auto& entry : fs::directory_iterator(kRoot / "configs")) read.push_back(entry.path());
  for (const fs::path& path : read) {
    const std::string name = path.filename().string();
    if (name == "citing.md" || name == "paper_in_code.md") continue;
    const std::vector<std::string> lines = linesOf(readFile(path));
    for (std::size_t i = 0; i < lines.size(); ++i)
      for (const std::string& label : labels)
        EXPECT_EQ(lines[i].find(label), std::string::npos)
            << name << ":" << i + 1 << " names \"" << label
            << "\", not the paper's printed number: " << lines[i];
  }
}

}  // namespace
}  // namespace lagrange::testing
