// texproc build: runs the jobs of a recipe (docs/recipes.md). Each job is
// the command line `texproc COMMAND INPUTS -o OUTPUT --OPTION VALUE...`,
// parsed by the same parser as the command itself, so a recipe accepts
// exactly what the command line does and its mistakes are named with the
// recipe's line and key.
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "batch.h"
#include "report.h"
#include "commands.h"
#include "common.h"
#include "recipe.h"
#include "texproc/error.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct BuildArgs {
  CommonOptions common;
  std::string recipe, out_dir;
  std::vector<std::string> only;
};

// Options that belong to the run, not to a job: given on the build command
// line, they apply to every job.
bool run_level_option(const std::string& key) {
  static const char* keys[] = {"threads", "jobs",     "j",         "force",         "f",           "quiet",
                               "q",       "verbose",  "v",         "depfile",       "dry-run",     "n",
                               "json",    "progress", "fail-fast", "skip-existing", "write-if-changed",
                               "output",  "o",        "recursive", "r",             "file-list",   "help",
                               "h"};
  return std::any_of(std::begin(keys), std::end(keys), [&](const char* k) { return key == k; });
}

// Where in the recipe a message about a job points: the option it names
// ("--format"), else the job.
std::string locate(const Recipe& r, const RecipeJob& j, const std::string& message) {
  for (const RecipeOption& o : j.options) {
    const std::string flag = "--" + o.key;
    const auto at = message.find(flag);
    if (at != std::string::npos) {
      const std::size_t end = at + flag.size();
      const bool whole = end == message.size() || !(std::isalnum(static_cast<unsigned char>(message[end])) ||
                                                    message[end] == '-' || message[end] == '_');
      if (whole) return where(r, j, o.line) + ": options." + o.key;
    }
  }
  return where(r, j, 0);
}

struct PreparedJob {
  const RecipeJob* job = nullptr;
  std::unique_ptr<CLI::App> app;
  CLI::App* command = nullptr;
};

PreparedJob prepare(const Recipe& r, const RecipeJob& j, const CommonOptions& common) {
  PreparedJob p;
  p.job = &j;
  p.app = std::make_unique<CLI::App>();
  add_all_commands(*p.app);
  const std::vector<std::string> valid = {"mip", "compress", "normalmap", "conemap", "sat", "sat blur", "decompress", "cubemap"};
  if (std::find(valid.begin(), valid.end(), j.command) == valid.end()) {
    throw Error(ErrorCode::bad_arguments, where(r, j, j.command_line) + ": command: unknown command '" + j.command +
                                              "' (valid: " + join(valid) + ")");
  }
  std::vector<std::string> args;
  if (j.command == "sat blur") {
    p.command = p.app->get_subcommand("sat")->get_subcommand("blur");
    args = {"sat", "blur"};
  } else {
    p.command = p.app->get_subcommand(j.command);
    args = {j.command};
  }
  args.insert(args.end(), j.inputs.begin(), j.inputs.end());
  args.insert(args.end(), {"-o", j.output});
  if (j.recursive) args.push_back("-r");
  for (const RecipeOption& o : j.options) {
    const std::string at = where(r, j, o.line) + ": options." + o.key;
    if (run_level_option(o.key)) {
      throw Error(ErrorCode::bad_arguments, at + ": belongs to the whole run: give it to `texproc build` instead");
    }
    const CLI::Option* opt = p.command->get_option_no_throw("--" + o.key);
    if (!opt) {
      throw Error(ErrorCode::bad_arguments,
                  at + ": unknown option for " + j.command + " (see `texproc " + j.command + " --help`)");
    }
    const bool is_flag = opt->get_expected_max() == 0;
    if (is_flag && !o.flag) throw Error(ErrorCode::bad_arguments, at + ": is a switch: write " + o.key + " = true");
    if (!is_flag && o.flag) throw Error(ErrorCode::bad_arguments, at + ": needs a value, not true");
    args.push_back("--" + o.key);
    args.insert(args.end(), o.values.begin(), o.values.end());
  }
  // The run-level options each job's own parser holds.
  if (common.threads > 0) args.insert(args.end(), {"--threads", std::to_string(common.threads)});
  if (common.force) args.push_back("--force");
  if (common.quiet) args.push_back("--quiet");
  if (common.verbose) args.push_back("--verbose");
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last first
  try {
    p.app->parse(args);
  } catch (const CLI::ParseError& e) {
    throw Error(ErrorCode::bad_arguments, locate(r, j, e.what()) + ": " + e.what());
  }
  return p;
}

// The outputs a recipe has written, kept beside them in
// ".RECIPE_FILE_NAME.outputs" (one path a line, relative to the folder the
// outputs are taken from), so that an incremental build replaces only files
// it made, never a source that a job's output happens to name.
struct OwnedOutputs {
  fs::path root, file;
  std::set<std::string> keys;  // output_key of each
  std::vector<std::string> lines;

  OwnedOutputs(const std::string& recipe, const std::string& out_dir) {
    root = out_dir.empty() ? fs::path(recipe).parent_path() : fs::path(out_dir);
    if (root.empty()) root = ".";
    file = root / ("." + fs::path(recipe).filename().string() + ".outputs");
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
      if (!line.empty()) add_relative(line);
    }
  }
  void add_relative(const std::string& rel) {
    if (keys.insert(output_key((root / rel).string())).second) lines.push_back(rel);
  }
  void add(const std::string& output) {
    std::error_code ec;
    const fs::path rel = fs::relative(fs::absolute(output, ec), fs::absolute(root, ec), ec);
    add_relative(ec || rel.empty() ? fs::absolute(output).lexically_normal().string() : rel.string());
  }
  void save() const {
    std::string text;
    for (const std::string& l : lines) text += l + "\n";
    std::error_code ec;
    fs::create_directories(root, ec);
    write_file_atomic(file.string(), text, CommitPolicy::replace);
  }
};

// Before any job runs: no output of one job may be a file that another job
// reads, unless this recipe made it (an intermediate).
void check_outputs_against_inputs(const Recipe& r, const std::vector<PreparedJob>& jobs,
                                  const std::vector<std::vector<SessionOptions::PlannedFile>>& plans,
                                  const OwnedOutputs& owned) {
  std::map<std::pair<dev_t, ino_t>, std::size_t> reader;  // an input file -> the job that reads it
  for (std::size_t j = 0; j < plans.size(); ++j) {
    for (const auto& f : plans[j]) {
      for (const std::string& in : f.inputs) {
        struct stat st {};
        if (::stat(in.c_str(), &st) == 0) reader.emplace(std::pair{st.st_dev, st.st_ino}, j);
      }
    }
  }
  for (std::size_t j = 0; j < plans.size(); ++j) {
    for (const auto& f : plans[j]) {
      for (const std::string& out : f.outputs) {
        struct stat st {};
        if (::stat(out.c_str(), &st) != 0 || owned.keys.count(output_key(out))) continue;
        const auto it = reader.find({st.st_dev, st.st_ino});
        if (it == reader.end()) continue;
        throw Error(ErrorCode::bad_arguments,
                    where(r, *jobs[j].job, jobs[j].job->output_line) + ": output " + out + " is an input of " +
                        where(r, *jobs[it->second].job, 0) +
                        " and was not made by this recipe; outputs never overwrite sources: choose another name");
      }
    }
  }
}

// The command whose runner runs the job (`sat` for `sat blur`).
CLI::App* top_command(const PreparedJob& p) {
  return p.command->get_parent() == p.app.get() ? p.command : p.command->get_parent();
}

int run_build(const BuildArgs& a) {
  const Recipe recipe = read_recipe(a.recipe, a.out_dir);
  record_input(a.recipe);
  for (const auto& name : a.only) {
    if (std::none_of(recipe.jobs.begin(), recipe.jobs.end(), [&](const RecipeJob& j) { return j.name == name; })) {
      throw Error(ErrorCode::bad_arguments, a.recipe + ": --job " + name + ": no job has that name");
    }
  }
  // Every job is parsed before any runs: a mistake anywhere stops the build
  // before it writes anything.
  std::vector<PreparedJob> jobs;
  for (const RecipeJob& j : recipe.jobs) {
    if (!a.only.empty() && std::find(a.only.begin(), a.only.end(), j.name) == a.only.end()) continue;
    jobs.push_back(prepare(recipe, j, a.common));
  }
  // Incremental unless --force: up-to-date files are skipped, changed ones
  // rebuilt, and only outputs this recipe made may be replaced.
  OwnedOutputs owned(a.recipe, a.out_dir);
  SessionOptions& s = session_options();
  s.incremental = !a.common.force;
  s.run_inputs = {a.recipe};
  s.owned_outputs = owned.keys;
  // A first pass checks each job's option values, inputs and output names,
  // and plans every file, so that no output overwrites any job's input.
  std::vector<std::vector<SessionOptions::PlannedFile>> plans(jobs.size());
  s.check_only = true;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    s.plans = &plans[j];
    try {
      (*runner_of(*top_command(jobs[j])))();
    } catch (const Error& e) {
      s.check_only = false;
      s.plans = nullptr;
      throw Error(e.code(), locate(recipe, *jobs[j].job, e.what()) + ": " + e.what());
    }
  }
  s.check_only = false;
  s.plans = nullptr;
  check_outputs_against_inputs(recipe, jobs, plans, owned);
  int rc = 0;
  for (PreparedJob& p : jobs) {
    const std::size_t first = session_reports().size();
    int job_rc = 0;
    try {
      job_rc = (*runner_of(*top_command(p)))();
    } catch (const Error& e) {
      print_error("build", locate(recipe, *p.job, e.what()) + ": " + in_cli_terms(e.what()));
      job_rc = int(e.code());
    }
    const std::string name = p.job->name.empty() ? "jobs[" + std::to_string(p.job->index) + "]" : p.job->name;
    bool wrote = false;
    for (std::size_t i = first; i < session_reports().size(); ++i) {
      FileReport& fr = session_reports()[i];
      fr.details["job"] = name;
      if (fr.status != "ok" || dry_run()) continue;
      for (const std::string& o : fr.outputs) owned.add(o);
      wrote = true;
    }
    if (wrote) {
      owned.save();
      s.owned_outputs = owned.keys;
    }
    if (job_rc != 0 && rc == 0) rc = job_rc;
    if (job_rc != 0 && session_options().fail_fast) break;
  }
  return rc;
}

}  // namespace

void add_build_command(CLI::App& app) {
  auto args = std::make_shared<BuildArgs>();
  CLI::App* cmd = app.add_subcommand("build", "Run the jobs of a recipe (TOML or JSON): a project's texture settings.");
  cmd->footer(
      "A recipe lists jobs: command, inputs (files, folders, glob patterns), output (file, folder/ or\n"
      "template) and options, as on the command line. Paths are relative to the recipe's folder.\n"
      "Run-level options (--threads, --jobs, --force, --depfile, --dry-run, --json...) are given here and\n"
      "apply to every job. See docs/recipes.md and samples/recipe.toml.");
  cmd->add_option("recipe", args->recipe, "Recipe file (.toml or .json)")->required();
  cmd->add_option("--out-dir", args->out_dir,
                  "Take relative outputs from this folder instead of the recipe's (out-of-source builds)");
  cmd->add_option("--job", args->only, "Run only the jobs with these names (repeatable)");
  add_common_options(*cmd, args->common);
  set_runner(*cmd, [args] { return run_build(*args); });
}

}  // namespace texproc::cli
