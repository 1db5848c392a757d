// The inputs and outputs of a batch: folder arguments and file lists
// expanded into files, and each file's output named (one file, a folder
// that mirrors the inputs' subfolders, or a template).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "batch.h"
#include "texproc/error.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc::cli {

bool is_template(const std::string& output) { return output.find('{') != std::string::npos; }

std::string expand_template(const std::string& pattern, const InputFile& in) {
  const fs::path p(in.path);
  std::string ext = p.extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  std::string dir = p.parent_path().string();
  if (dir.empty()) dir = ".";
  const std::string reldir = in.reldir.empty() ? "." : in.reldir;
  std::string out;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const char c = pattern[i];
    if ((c == '{' || c == '}') && i + 1 < pattern.size() && pattern[i + 1] == c) {
      out += c;
      ++i;
      continue;
    }
    if (c != '{') {
      out += c;
      continue;
    }
    const std::size_t close = pattern.find('}', i);
    if (close == std::string::npos) {
      throw Error(ErrorCode::bad_arguments, "-o '" + pattern + "': '{' without '}' (write {{ for a literal brace)");
    }
    const std::string key = pattern.substr(i + 1, close - i - 1);
    if (key == "stem")
      out += p.stem().string();
    else if (key == "name")
      out += p.filename().string();
    else if (key == "ext")
      out += ext;
    else if (key == "dir")
      out += dir;
    else if (key == "reldir")
      out += reldir;
    else {
      throw Error(ErrorCode::bad_arguments, "-o '" + pattern + "': unknown placeholder {" + key +
                                                "} (valid: {stem}, {name}, {ext}, {dir}, {reldir})");
    }
    i = close;
  }
  return fs::path(out).lexically_normal().string();
}

namespace {

std::string lower(std::string s) {
  for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool wanted(const fs::path& p, const std::vector<std::string>& extensions) {
  const std::string name = p.filename().string();
  if (name.empty() || name[0] == '.') return false;  // hidden files and our own temporaries
  const std::string e = lower(p.extension().string());
  return std::find(extensions.begin(), extensions.end(), e) != extensions.end();
}

// The files a folder argument stands for, sorted by path (the same order on
// every machine).
void add_folder(const std::string& folder, bool recursive, const std::vector<std::string>& extensions,
                std::vector<InputFile>& out) {
  std::vector<InputFile> found;
  std::error_code ec;
  auto take = [&](const fs::directory_entry& e) {
    if (!e.is_regular_file(ec) || !wanted(e.path(), extensions)) return;
    const fs::path rel = e.path().lexically_relative(folder).parent_path();
    found.push_back({e.path().lexically_normal().string(), rel.empty() ? "" : rel.string()});
  };
  if (recursive) {
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string n = it->path().filename().string();
      if (!n.empty() && n[0] == '.' && it->is_directory(ec)) {
        it.disable_recursion_pending();  // .git and friends
        continue;
      }
      take(*it);
    }
  } else {
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) take(*it);
  }
  if (ec) throw Error(ErrorCode::io, folder + ": cannot list folder: " + ec.message());
  std::sort(found.begin(), found.end(), [](const InputFile& a, const InputFile& b) { return a.path < b.path; });
  if (found.empty()) {
    throw Error(ErrorCode::bad_arguments, folder + ": folder holds no input files (" + join(extensions, " ") + ")" +
                                              (recursive ? "" : "; -r searches its subfolders"));
  }
  out.insert(out.end(), found.begin(), found.end());
}

}  // namespace

std::vector<std::string> name_outputs(const BatchCommand& c, const BatchInputs& b,
                                      const std::vector<InputFile>& files) {
  std::vector<std::string> outs;
  std::error_code ec;
  const std::string& o = b.output;
  const bool folder = !is_template(o) && (o.back() == '/' || fs::is_directory(o, ec) ||
                                          (files.size() > 1 && fs::path(o).extension().empty()));
  if (!is_template(o) && !folder && files.size() > 1) {
    throw Error(ErrorCode::bad_arguments, "-o " + o + " names one file, but there are " + std::to_string(files.size()) +
                                              " inputs; use -o DIR/ or a template "
                                              "such as -o 'out/{stem}" +
                                              c.default_extension + "'");
  }
  for (const auto& f : files) {
    if (is_template(o)) {
      outs.push_back(expand_template(o, f));
    } else if (folder) {
      // The folder mirrors the inputs' subfolders under a folder argument.
      const std::string ext = c.default_extension.empty() ? fs::path(f.path).extension().string() : c.default_extension;
      outs.push_back((fs::path(o) / f.reldir / (fs::path(f.path).stem().string() + ext)).lexically_normal().string());
    } else {
      outs.push_back(o);
    }
  }
  return outs;
}

std::vector<InputFile> expand_inputs(const BatchInputs& b, const std::vector<std::string>& extensions) {
  std::vector<std::string> args = b.inputs;
  if (!b.file_list.empty()) {
    std::ifstream list(b.file_list);
    if (!list) throw Error(ErrorCode::io, b.file_list + ": cannot open file list");
    record_input(b.file_list);
    std::string line;
    while (std::getline(list, line)) {
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      const auto last = line.find_last_not_of(" \t\r");
      args.push_back(line.substr(first, last - first + 1));
    }
  }
  if (args.empty()) throw Error(ErrorCode::bad_arguments, "no inputs: name files or folders, or use --file-list");
  std::vector<InputFile> files;
  std::error_code ec;
  for (const auto& a : args) {
    if (fs::is_directory(a, ec)) {
      add_folder(a, b.recursive, extensions, files);
    } else {
      files.push_back({a, ""});  // a missing file fails on its own, later
    }
  }
  return files;
}

}  // namespace texproc::cli
