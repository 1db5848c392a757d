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
  bool flag = false;  // true: a boolean true (the flag is given)
  bool off = false;   // a boolean false: the switch is off (removes a default's `true`)
  int line = 0;
};

// `top`'s options replacing `base`'s of the same key, the switches that
// are off left out.
std::vector<RecipeOption> merge_options(const std::vector<RecipeOption>& base, const std::vector<RecipeOption>& top);

// One entry of a job's `inputs`: a file, a folder (ending in / or found to
// be one) or a glob pattern (`*`, `?`, `[...]`, and `**` for any number of
// folders), resolved against the recipe's folder.
struct InputSpec {
  std::string text;  // as written
  std::string path;  // resolved
  bool glob = false;
  int line = 0;
  // With --out-dir: the same text resolved against the output folder, where
  // another job's outputs are (an intermediate is looked for there first).
  std::string alt;
  std::string base, alt_base;  // the two folders, absolute
};

// Options for some of a job's files: those matching `patterns` (files or
// globs, resolved) run with the job's options and these on top.
struct RecipeOverride {
  std::vector<std::string> patterns;
  std::vector<RecipeOption> options;
  int line = 0;
};

struct RecipeJob {
  int index = 0;  // 0-based position in `jobs`
  int line = 0;
  std::string name;     // for messages; "jobs[N]" if not set
  std::string command;  // mip, compress, ...
  std::vector<InputSpec> inputs;
  std::vector<std::string> excludes;  // glob patterns (resolved): files matching one are left out
  std::string output;                 // resolved against the recipe's folder
  bool recursive = false;
  std::vector<RecipeOption> options;  // the recipe's defaults for the command, then the job's own
  std::vector<RecipeOverride> overrides;
  int command_line = 0, output_line = 0;
  // With --out-dir: the recipe's folder and the output folder (absolute);
  // excludes and overrides name a file made under the output folder by its
  // path under the recipe's folder.
  std::string source_base, output_base;
};

struct Recipe {
  std::string path;
  std::vector<RecipeJob> jobs;
};

// Reads and checks a recipe's structure (keys, types; version 1). Relative
// paths are taken from the recipe's folder (outputs: from `out_dir` if
// given). Glob patterns are kept as patterns: they are expanded by
// expand_inputs(), against the files on disk and the outputs other jobs
// will write. Errors are
// Error{bad_arguments} "FILE:LINE: jobs[N].key: what is wrong"
// (Error{io} when the file cannot be read).
// `out_dir`: relative outputs are taken from it instead (out-of-source
// builds); empty: the recipe's folder.
Recipe read_recipe(const std::string& path, const std::string& out_dir = "");

// Whether `path` matches the glob `pattern`, a path segment at a time
// (fnmatch without crossing '/', a leading '.' only matched explicitly);
// a `**` segment matches any number of folders, none included.
bool glob_match(const std::string& pattern, const std::string& path);

// The job's inputs as command-line arguments: files and folders as
// written; each glob replaced by the files it matches on disk and among
// `planned` (outputs other jobs will write, absolute and normalized), sorted,
// less the job's excludes. With an output folder (--out-dir), a planned
// output there stands in for the same path under the recipe's folder. Patterns that match nothing are appended to
// `unmatched` (when given) and contribute nothing.
std::vector<std::string> expand_job_inputs(const RecipeJob& j, const std::vector<std::string>& planned,
                                           std::vector<const InputSpec*>* unmatched = nullptr);

// Whether a file is one of the job's excluded files.
bool excluded(const RecipeJob& j, const std::string& file);

// The override (index) that applies to `file`, or -1.
int override_of(const RecipeJob& j, const std::string& file);

// "recipe.toml:12: job 'albedo'" for messages.
std::string where(const Recipe& r, const RecipeJob& j, int line);

}  // namespace texproc::cli
