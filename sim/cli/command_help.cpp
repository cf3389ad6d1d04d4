#include "sim/cli/command_help.hpp"

#include <algorithm>
#include <map>

namespace vmt::sim {
namespace {

// One example per subcommand path, runnable from a clone (the scenes and models it ships).
const std::map<std::string, std::string>& Examples() {
  static const std::map<std::string, std::string> examples = {
      {"run", "vmt run scenes/default.yaml --out out/default"},
      {"snapshot", "vmt snapshot scenes/default.yaml --at 12 --camera work --out work.png"},
      {"check", "vmt check scenes/nc/shaft_with_repos.mtc"},
      {"signals", "vmt signals models/lathe-c1/machine.yaml --format csv > signals.csv"},
      {"serve",
       "vmt serve examples/plc/minimal_plc.yaml --modbus 127.0.0.1:5020   (then your PLC)\n"
       "  vmt serve scenes/station.yaml --http 127.0.0.1:8080          (then open the page)"},
      {"view", "vmt view out/default --http 127.0.0.1:8080"},
      {"imgdiff", "vmt imgdiff golden.png actual.png --diff diff.png"},
      {"golden check",
       "vmt golden check scenes/default.yaml --golden tests/golden --junit golden.xml"},
      {"golden update", "vmt golden update my-scene.yaml --golden my-goldens"},
      {"study repos", "vmt study repos scenes/study-repos-turning.yaml --out out/study --jobs 2"},
      {"study merge", "vmt study merge out/s1 out/s2 --out out/study"},
      {"study replay",
       "vmt study replay out/study CASE_ID --http 127.0.0.1:8080   (CASE_ID: cases.csv, "
       "first column)"},
      {"study compare", "vmt study compare out/study-a out/study-b --html compare.html"},
  };
  return examples;
}

void AddExamplesUnder(CLI::App& app, const std::string& prefix) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    const std::string path = prefix.empty() ? sub->get_name() : prefix + " " + sub->get_name();
    const auto it = Examples().find(path);
    if (it != Examples().end()) {
      const std::string footer = sub->get_footer();
      sub->footer((footer.empty() ? "" : footer + "\n\n") + "Example:\n  " + it->second);
    }
    AddExamplesUnder(*sub, path);
  }
}

bool IsSubsequence(const std::string& part, const std::string& whole) {
  size_t at = 0;
  for (const char c : whole)
    if (at < part.size() && part[at] == c) ++at;
  return at == part.size() && part.size() >= 2;
}

}  // namespace

void AddExamples(CLI::App& app) {
  app.footer(
      "Start with:\n  vmt run scenes/default.yaml --out out/default\n"
      "Each command's --help has an example; all of them: docs/cli.md");
  AddExamplesUnder(app, "");
}

int EditDistance(const std::string& a, const std::string& b) {
  // Optimal string alignment: a swapped pair of neighbours ("rnu") costs one edit.
  std::vector<std::vector<int>> d(a.size() + 1, std::vector<int>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = static_cast<int>(i);
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

CommandWords ReadCommandWords(CLI::App& app, const std::vector<std::string>& args) {
  CommandWords words;
  CLI::App* level = &app;
  for (const std::string& arg : args) {
    const auto subs = level->get_subcommands([](CLI::App*) { return true; });
    if (subs.empty() || arg.empty() || arg[0] == '-') break;
    const auto named =
        std::find_if(subs.begin(), subs.end(), [&](CLI::App* s) { return s->get_name() == arg; });
    if (named != subs.end()) {
      words.path.push_back(arg);
      level = *named;
      continue;
    }
    words.unknown = arg;
    // A slip: the start of a name ("st"), its letters in order with some left out ("rn",
    // "sigs"), or a few letters wrong ("chek", "rpos"): at most a third of the word's letters.
    int best = static_cast<int>(arg.size()) / 3 + 2;
    for (CLI::App* s : subs) {
      const std::string& name = s->get_name();
      int score = EditDistance(arg, name) + 1;
      if (IsSubsequence(arg, name)) score = 1;
      if (arg.size() >= 2 && name.rfind(arg, 0) == 0) score = 0;
      if (score < best) {
        best = score;
        words.suggestion = name;
      }
    }
    break;
  }
  return words;
}

}  // namespace vmt::sim
