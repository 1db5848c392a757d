// Recipes: a project's texture settings in one version-controlled file
// (TOML or JSON), run by `texproc build`. Schema in docs/recipes.md.
#pragma once

#include <string>
#include <vector>

namespace texproc::cli {

// An option of a job: `--key` with its values (none for a flag).
struct RecipeOption {
  std::string key;
  std::vector<std::string> values;
  bool flag = false;  // true: a boolean true (the flag is given); false booleans are dropped
  int line = 0;
};

struct RecipeJob {
  int index = 0;  // 0-based position in `jobs`
  int line = 0;
  std::string name;     // for messages; "jobs[N]" if not set
  std::string command;  // mip, compress, ...
  std::vector<std::string> inputs;  // resolved against the recipe's folder; globs expanded
  std::vector<int> input_lines;
  std::string output;  // resolved against the recipe's folder
  bool recursive = false;
  std::vector<RecipeOption> options;
  int command_line = 0, output_line = 0;
};

struct Recipe {
  std::string path;
  std::vector<RecipeJob> jobs;
};

// Reads and checks a recipe's structure (keys, types; version 1). Relative
// paths are taken from the recipe's folder (outputs: from `out_dir` if
// given); inputs with * ? [ are glob
// patterns and must match at least one file. Errors are
// Error{bad_arguments} "FILE:LINE: jobs[N].key: what is wrong"
// (Error{io} when the file cannot be read).
// `out_dir`: relative outputs are taken from it instead (out-of-source
// builds); empty: the recipe's folder.
Recipe read_recipe(const std::string& path, const std::string& out_dir = "");

// "recipe.toml:12: job 'albedo'" for messages.
std::string where(const Recipe& r, const RecipeJob& j, int line);

}  // namespace texproc::cli
