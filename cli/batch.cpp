#include "batch.h"
#include "report.h"

#include "texproc/tools.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "progress.h"
#include "texproc/runtime.h"

namespace fs = std::filesystem;

namespace texproc::cli {

BatchSession& batch_session() {
  static BatchSession s;
  return s;
}

std::vector<FileReport>& session_reports() {
  static std::vector<FileReport> r;
  return r;
}

void add_batch_inputs(CLI::App& cmd, BatchInputs& b, const char* what, const char* output_help, bool output_required) {
  cmd.add_option("inputs", b.inputs, std::string(what) + ": files, or folders (their files; with -r, recursively)");
  cmd.add_option("-o,--output", b.output, output_help)->required(output_required);
  cmd.add_flag("-r,--recursive", b.recursive, "Folder inputs: take the files of their subfolders too")->group("Batch");
  cmd.add_option("--file-list", b.file_list, "Read more inputs from FILE, one a line ('#' starts a comment)")
      ->group("Batch");
}

namespace {

// Every failure of a file: in the command line's terms, the file in front.
void fail(FileReport& r, ErrorCode code, const std::string& message) {
  r.status = FileStatus::failed;
  r.code = code;
  r.error = about(r.input, in_cli_terms(message));
}

// Every file planned (names, existence, overwrites) before any work; a
// file that cannot be planned is failed with its reason.
std::vector<FileReport> plan_files(const BatchCommand& c, const std::vector<InputFile>& files,
                                   const std::vector<std::string>& outputs,
                                   const std::vector<std::string>& shared_inputs) {
  std::vector<FileReport> reports(files.size());
  std::error_code ec;
  for (std::size_t i = 0; i < files.size(); ++i) {
    FileReport& r = reports[i];
    r.input = files[i].path;
    r.inputs.push_back(r.input);
    r.inputs.insert(r.inputs.end(), shared_inputs.begin(), shared_inputs.end());
    try {
      if (!fs::is_regular_file(r.input, ec)) {
        // --dry-run of a recipe: made by an earlier job first.
        const auto made = batch_session().pending.find(absolute_path(r.input));
        if (made != batch_session().pending.end()) {
          r.outputs = {outputs[i]};
          r.details["reason"] = "input made by job " + made->second;
          continue;
        }
        throw Error(ErrorCode::io, r.input + (fs::exists(r.input, ec) ? ": not a file" : ": no such file"));
      }
      r.outputs = c.plan(files[i], outputs[i]);
    } catch (const Error& e) {
      fail(r, e.code(), e.what());
    }
  }
  return reports;
}

// What a file's run writes: its planned outputs, or the output it was named.
std::vector<std::string> claimed_outputs(const FileReport& r, const std::string& output) {
  return r.outputs.empty() ? std::vector{output} : r.outputs;
}

// No output may be a file that any input of this run is (the same file
// through a symlink, "..", or a hard link: compared by device and inode),
// checked before any work, whatever --force says.
void check_no_input_overwritten(const std::vector<FileReport>& reports, const std::vector<std::string>& outputs) {
  std::map<std::pair<dev_t, ino_t>, std::string> input_files;
  for (const FileReport& r : reports) {
    for (const std::string& in : r.inputs) {
      struct stat st {};
      if (::stat(in.c_str(), &st) == 0) input_files.emplace(std::pair{st.st_dev, st.st_ino}, in);
    }
  }
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const std::vector<std::string> claimed = claimed_outputs(reports[i], outputs[i]);
    for (const auto& o : claimed) {
      struct stat st {};
      std::error_code wc;
      if (::stat(o.c_str(), &st) != 0) continue;
      const auto it = input_files.find({st.st_dev, st.st_ino});
      if (it == input_files.end()) continue;
      const bool own = fs::equivalent(reports[i].input, it->second, wc);
      throw Error(ErrorCode::bad_arguments,
                  o + ": output would overwrite the input " + it->second +
                      (own ? "" : " (another input of this run: " + reports[i].input + " writes here)") +
                      "; outputs never overwrite inputs: choose another name or folder");
    }
  }
}

// One writer per output (extra outputs such as a preview included),
// before any folder is made; names compared after symlinks and "..".
void check_one_writer(const std::vector<FileReport>& reports, const std::vector<std::string>& outputs) {
  std::map<std::string, std::size_t> writer;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const std::vector<std::string> claimed = claimed_outputs(reports[i], outputs[i]);
    for (const auto& o : claimed) {
      std::error_code wc;
      fs::path key = fs::weakly_canonical(fs::absolute(o, wc), wc);
      if (wc) key = fs::path(o).lexically_normal();
      auto [it, fresh] = writer.emplace(key.string(), i);
      if (!fresh && it->second != i) {
        throw Error(ErrorCode::bad_arguments, o + ": both " + reports[it->second].input + " and " + reports[i].input +
                                                  " would write this output; name outputs with a template ({stem}, "
                                                  "{name}, {dir})");
      }
    }
  }
}

// Up to date: every output exists and none is older than any input (the
// file's, an OCIO config among them, and the recipe's).
bool up_to_date(const FileReport& r, const BatchSession& s) {
  std::error_code ec;
  fs::file_time_type newest_input = fs::file_time_type::min();
  bool inputs_known = true;
  std::vector<std::string> deps = r.inputs;
  deps.insert(deps.end(), s.run_inputs.begin(), s.run_inputs.end());
  for (const std::string& in : deps) {
    const auto t = fs::last_write_time(in, ec);
    if (ec)
      inputs_known = false;
    else
      newest_input = std::max(newest_input, t);
  }
  return inputs_known && !r.outputs.empty() &&
         std::all_of(r.outputs.begin(), r.outputs.end(), [&](const std::string& f) {
           const auto t = fs::last_write_time(f, ec);
           return !ec && t >= newest_input;
         });
}

// --dry-run of a recipe: "input X rebuilt by job Y" when an earlier job
// would rewrite one of the file's inputs.
std::string rebuilt_input(const FileReport& r, const BatchSession& s) {
  if (s.pending.empty()) return "";
  for (const std::string& in : r.inputs) {
    const auto it = s.pending.find(absolute_path(in));
    if (it != s.pending.end()) return "input " + in + " rebuilt by job " + it->second;
  }
  return "";
}

// The files to run: not failed, not skipped (--incremental, --skip-existing),
// their outputs free to write.
std::vector<std::size_t> select_work(std::vector<FileReport>& reports, const BatchSession& s, const RunOptions& o) {
  std::error_code ec;
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    FileReport& r = reports[i];
    if (r.status == FileStatus::failed) continue;
    if (r.details.isMember("reason")) {
      // decided while planning
    } else if (const std::string by = rebuilt_input(r, s); !by.empty()) {
      r.details["reason"] = by;
    } else if (s.incremental && !o.force) {
      if (s.why_rebuild) {
        const std::string why = s.why_rebuild(r);
        if (why.empty()) {
          r.status = FileStatus::skipped;
          continue;
        }
        r.details["reason"] = why;
      } else if (up_to_date(r, s)) {
        r.status = FileStatus::skipped;
        continue;
      }
    }
    if (o.skip_existing &&
        std::all_of(r.outputs.begin(), r.outputs.end(), [&](const std::string& f) { return fs::exists(f, ec); })) {
      r.status = FileStatus::skipped;
      continue;
    }
    try {
      for (const auto& out : r.outputs) {
        // An incremental build replaces only what it made itself.
        const bool replace = o.force || (s.incremental && s.owned_outputs.count(output_key(out)));
        if (s.incremental && !replace && fs::exists(out, ec)) {
          throw Error(ErrorCode::bad_arguments, out +
                                                    ": output exists and was not written by this recipe; --force "
                                                    "replaces it");
        }
        check_output(out, {r.input}, replace);
      }
      todo.push_back(i);
    } catch (const Error& e) {
      fail(r, e.code(), e.what());
    }
  }
  return todo;
}

// One file's work (on a worker thread): any failure is the file's, its
// warnings and phase times go into its report.
// An output's identity before the work, for --write-if-changed's report: an
// output kept unchanged is the same file (inode) with the same time stamp.
struct Identity {
  bool exists = false;
  ino_t inode = 0;
  struct timespec mtime {};
};
Identity identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return {};
  return {true, st.st_ino, st.st_mtim};
}

// --write-if-changed: which outputs were kept (their bytes would not change)
// and which replaced, in the file's line and in its JSON details.
void report_kept(FileReport& r, const std::vector<Identity>& before) {
  Json::Value kept(Json::arrayValue), replaced(Json::arrayValue);
  for (std::size_t i = 0; i < r.outputs.size() && i < before.size(); ++i) {
    const Identity now = identity(r.outputs[i]);
    const bool same = before[i].exists && now.exists && now.inode == before[i].inode &&
                      now.mtime.tv_sec == before[i].mtime.tv_sec && now.mtime.tv_nsec == before[i].mtime.tv_nsec;
    (same ? kept : replaced).append(r.outputs[i]);
  }
  r.details["kept"] = kept;
  r.details["replaced"] = replaced;
  if (r.line.empty()) return;
  const std::string note = replaced.empty() ? " (unchanged: kept)"
                           : kept.empty()   ? " (written)"
                                            : " (" + std::to_string(kept.size()) + " kept unchanged, " +
                                                std::to_string(replaced.size()) + " written)";
  const std::size_t nl = r.line.find('\n');
  r.line.insert(nl == std::string::npos ? r.line.size() : nl, note);
}

void run_file(const BatchCommand& c, FileReport& r, const std::string& output, CommitPolicy policy) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Identity> before;
  if (run_options().write_if_changed) {
    for (const std::string& o : r.outputs) before.push_back(identity(o));
  }
  try {
    // The file's outputs are put in place together once all are written,
    // or none is.
    CommitGroup outputs(policy);
    c.run(r.input, output, r);
    outputs.commit();
    if (run_options().write_if_changed) report_kept(r, before);
  } catch (const Error& e) {
    fail(r, e.code(), e.what());
  } catch (const std::bad_alloc&) {
    fail(r, ErrorCode::runtime, r.input + ": out of memory");
  } catch (const std::exception& e) {
    fail(r, ErrorCode::runtime, r.input + ": " + e.what());
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!r.warnings.empty()) {
    Json::Value w(Json::arrayValue);
    for (const std::string& m : r.warnings) w.append(m);
    r.details["warnings"] = w;
  }
  if (r.phases.read >= 0) {
    Json::Value ph(Json::objectValue);
    ph["read_ms"] = r.phases.read;
    ph["compute_ms"] = r.phases.compute;
    ph["write_ms"] = r.phases.write;
    r.details["phases"] = ph;
    if (run_options().verbose && !r.line.empty()) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "\n  read %.1f ms, compute %.1f ms, write %.1f ms", r.phases.read,
                    r.phases.compute, r.phases.write);
      const std::size_t nl = r.line.find('\n');
      r.line.insert(nl == std::string::npos ? r.line.size() : nl, buf);
    }
  }
}

// Files the options name (an OpenColorIO config, a radius map) are inputs
// of every output: what validate() records, and the config.
std::vector<std::string> validate_and_collect_shared_inputs(const BatchCommand& c, const RunOptions& o) {
  const std::size_t recorded_before = recorded_inputs().size();
  if (c.validate) c.validate();
  const std::vector<std::string> all_recorded = recorded_inputs();
  std::vector<std::string> shared(all_recorded.begin() + std::ptrdiff_t(recorded_before), all_recorded.end());
  if (!o.ocio_config.empty() && std::find(shared.begin(), shared.end(), o.ocio_config) == shared.end()) {
    shared.push_back(o.ocio_config);
    record_input(o.ocio_config);
  }
  return shared;
}

// The inputs this run works on: those `build` selected, then this shard's share.
std::vector<InputFile> this_runs_files(std::vector<InputFile> files, BatchSession& s, const RunOptions& o) {
  if (s.select) {
    files.erase(std::remove_if(files.begin(), files.end(), [&](const InputFile& f) { return !s.select(f.path); }),
                files.end());
  }
  if (o.shard_count > 0 && !s.check_only) {
    std::vector<InputFile> mine;
    for (const InputFile& f : files) {
      if (int(s.shard_counter++ % std::size_t(o.shard_count)) == o.shard_index) mine.push_back(f);
    }
    files = std::move(mine);
  }
  return files;
}

// --dry-run: each output that would be written (with change tracking, why).
void print_dry_run(const BatchCommand& c, const std::vector<FileReport>& reports, const RunOptions& o) {
  for (const auto& r : reports) {
    if (r.status == FileStatus::failed) {
      print_error(c.name, r.error);
    } else if (r.status != FileStatus::skipped && !o.json) {
      const std::string why = r.details.isMember("reason") ? " (" + r.details["reason"].asString() + ")" : "";
      for (const auto& out : r.outputs) std::cout << out << why << "\n";
    }
  }
}

// Prints the files that failed while planned; whether there were any.
bool print_plan_failures(const BatchCommand& c, const std::vector<FileReport>& reports) {
  bool failed = false;
  for (const auto& r : reports) {
    if (r.status != FileStatus::failed) continue;
    failed = true;
    print_error(c.name, r.error);
  }
  return failed;
}

// Runs the files in `todo` in parallel, reporting each in input order as it
// and those before it finish; files not started (--fail-fast) are not_run.
void run_files(const BatchCommand& c, std::vector<FileReport>& reports, const std::vector<std::size_t>& todo,
               const std::vector<std::string>& outputs, CommitPolicy policy, const RunOptions& o) {
  Progress progress(c.name, todo.size(), !o.quiet && (o.progress || ::isatty(2)));
  const int hw = hardware_threads();
  const std::size_t tokens = std::size_t(std::max(1, o.jobs > 0 ? o.jobs : (o.threads > 0 ? o.threads : hw)));
  const std::size_t started = for_each_in_order(
      todo.size(), tokens,
      [&](std::size_t k) {
        FileReport& r = reports[todo[k]];
        progress.started(r.input);
        r.progress = [&progress, &r](double done) { progress.fraction(r.input, done); };
        run_file(c, r, outputs[todo[k]], policy);
      },
      [&](std::size_t k) {
        FileReport& r = reports[todo[k]];
        progress.finished(r.input, [&] {
          if (!o.quiet && !o.json) {
            for (const std::string& w : r.warnings) print_warning(c.name, w);
          }
          if (r.status == FileStatus::failed) {
            print_error(c.name, r.error);
          } else if (!o.quiet && !o.json && !r.line.empty()) {
            std::cout << r.line << "\n" << std::flush;
          }
        });
        return !(r.status == FileStatus::failed && o.fail_fast);
      });
  progress.close();
  for (std::size_t k = started; k < todo.size(); ++k) reports[todo[k]].status = FileStatus::not_run;
}

// The run's exit code (the first failure's), the reports kept for the summary.
int finish_reports(const std::vector<FileReport>& reports) {
  int rc = 0;
  for (const auto& r : reports) {
    if (r.status == FileStatus::failed && rc == 0) rc = int(r.code);
    session_reports().push_back(r);
  }
  return rc;
}

}  // namespace

// The steps: validate the options, choose the files, name their outputs,
// plan every file (inputs, outputs, up to date or not) and check the plan
// as a whole (no output overwrites an input, one writer per output), then
// run what is out of date.
int run_batch(const BatchCommand& c, const BatchInputs& b) {
  const RunOptions& o = run_options();
  BatchSession& s = batch_session();
  ThreadLimit threads(o.threads);
  const std::vector<std::string> shared_inputs = validate_and_collect_shared_inputs(c, o);
  const std::vector<InputFile> files = this_runs_files(expand_inputs(b, c.input_extensions), s, o);
  if (files.empty() && (s.select || o.shard_count > 0)) return 0;  // none of them is this run's
  const std::vector<std::string> outputs = name_outputs(c, b, files);
  if (s.check_only) {
    if (s.plans) {
      const std::vector<FileReport> planned = plan_files(c, files, outputs, shared_inputs);
      for (std::size_t i = 0; i < planned.size(); ++i) {
        s.plans->push_back({files[i].path, outputs[i], planned[i].inputs, claimed_outputs(planned[i], outputs[i]),
                            planned[i].status != FileStatus::failed && !planned[i].outputs.empty()});
      }
    }
    return 0;
  }

  // Without --force (or --write-if-changed), an output that appears between
  // the check below and the end of the work is not replaced either: the
  // final rename refuses it atomically (two processes, one output).
  const CommitPolicy policy = o.write_if_changed         ? CommitPolicy::keep_identical
                              : o.force || s.incremental ? CommitPolicy::replace
                                                         : CommitPolicy::no_replace;
  std::vector<FileReport> reports = plan_files(c, files, outputs, shared_inputs);
  check_no_input_overwritten(reports, outputs);
  check_one_writer(reports, outputs);
  const std::vector<std::size_t> todo = select_work(reports, s, o);
  if (o.dry_run) {
    print_dry_run(c, reports, o);
    return finish_reports(reports);
  }
  // Plan failures are reported now; the work goes on for the others unless --fail-fast.
  if (print_plan_failures(c, reports) && o.fail_fast) {
    for (std::size_t i : todo) reports[i].status = FileStatus::not_run;
    return finish_reports(reports);
  }
  run_files(c, reports, todo, outputs, policy, o);
  return finish_reports(reports);
}

std::string absolute_path(const std::string& path) {
  std::error_code ec;
  const fs::path a = fs::absolute(path, ec);
  return (ec ? fs::path(path) : a).lexically_normal().string();
}

std::string output_key(const std::string& path) {
  std::error_code ec;
  const fs::path abs = fs::absolute(path, ec);
  if (ec) return fs::path(path).lexically_normal().string();
  const fs::path dir = fs::weakly_canonical(abs.parent_path(), ec);
  if (ec) return abs.lexically_normal().string();
  return (dir / abs.filename()).lexically_normal().string();
}

}  // namespace texproc::cli
