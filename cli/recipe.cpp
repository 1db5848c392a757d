#include "recipe.h"

#include <fnmatch.h>
#include <json/reader.h>
#include <json/value.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "texproc/error.h"

namespace fs = std::filesystem;

namespace texproc::cli {

namespace {

// The recipe as a plain tree with line numbers, from TOML or JSON.
struct Node {
  enum Kind { string, integer, real, boolean, array, table, other } kind = other;
  int line = 0;
  std::string text;  // string; numbers and booleans as written for the command line
  bool truth = false;
  std::vector<Node> items;
  std::vector<std::pair<std::string, Node>> fields;
  const Node* find(const std::string& key) const {
    for (const auto& [k, v] : fields)
      if (k == key) return &v;
    return nullptr;
  }
};

const char* kind_name(Node::Kind k) {
  switch (k) {
    case Node::string:
      return "a string";
    case Node::integer:
      return "an integer";
    case Node::real:
      return "a number";
    case Node::boolean:
      return "a boolean";
    case Node::array:
      return "an array";
    case Node::table:
      return "a table";
    case Node::other:
      return "a date or time";
  }
  return "?";
}

std::string number_text(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

Node from_toml(const toml::node& n) {
  Node out;
  out.line = int(n.source().begin.line);
  if (auto s = n.as_string()) {
    out.kind = Node::string;
    out.text = s->get();
  } else if (auto i = n.as_integer()) {
    out.kind = Node::integer;
    out.text = std::to_string(i->get());
  } else if (auto f = n.as_floating_point()) {
    out.kind = Node::real;
    out.text = number_text(f->get());
  } else if (auto flag = n.as_boolean()) {
    out.kind = Node::boolean;
    out.truth = flag->get();
    out.text = out.truth ? "true" : "false";
  } else if (auto list = n.as_array()) {
    out.kind = Node::array;
    for (const auto& item : *list) out.items.push_back(from_toml(item));
  } else if (auto t = n.as_table()) {
    out.kind = Node::table;
    for (const auto& [k, v] : *t) out.fields.emplace_back(std::string(k.str()), from_toml(v));
    // toml++ keeps keys sorted; present them in file order.
    std::stable_sort(out.fields.begin(), out.fields.end(),
                     [](const auto& a, const auto& b) { return a.second.line < b.second.line; });
  }
  return out;
}

Node from_json(const Json::Value& v, const std::vector<std::size_t>& line_starts) {
  Node out;
  const auto offset = std::size_t(std::max<std::ptrdiff_t>(0, v.getOffsetStart()));
  out.line = int(std::upper_bound(line_starts.begin(), line_starts.end(), offset) - line_starts.begin());
  switch (v.type()) {
    case Json::stringValue:
      out.kind = Node::string;
      out.text = v.asString();
      break;
    case Json::intValue:
    case Json::uintValue:
      out.kind = Node::integer;
      out.text = v.isInt64() ? std::to_string(v.asInt64()) : std::to_string(v.asUInt64());
      break;
    case Json::realValue:
      out.kind = Node::real;
      out.text = number_text(v.asDouble());
      break;
    case Json::booleanValue:
      out.kind = Node::boolean;
      out.truth = v.asBool();
      out.text = out.truth ? "true" : "false";
      break;
    case Json::arrayValue:
      out.kind = Node::array;
      for (const auto& item : v) out.items.push_back(from_json(item, line_starts));
      break;
    case Json::objectValue:
      out.kind = Node::table;
      for (const auto& k : v.getMemberNames()) out.fields.emplace_back(k, from_json(v[k], line_starts));
      std::stable_sort(out.fields.begin(), out.fields.end(),
                       [](const auto& a, const auto& b) { return a.second.line < b.second.line; });
      break;
    case Json::nullValue:
      out.kind = Node::other;
      break;
  }
  return out;
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw Error(ErrorCode::bad_arguments, path + ":" + std::to_string(line) + ": " + what);
}

Node parse_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::io, path + ": cannot open recipe");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::string ext = fs::path(path).extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".json") {
    Json::CharReaderBuilder b;
    b["rejectDupKeys"] = true;
    b["allowComments"] = true;
    b["failIfExtra"] = true;
    std::unique_ptr<Json::CharReader> reader(b.newCharReader());
    Json::Value root;
    std::string errors;
    if (!reader->parse(text.data(), text.data() + text.size(), &root, &errors)) {
      // jsoncpp says "* Line 3, Column 5\n  Syntax error: ...": make it FILE:LINE: message.
      std::string msg = errors;
      int line = 0;
      const auto at = msg.find("Line ");
      if (at != std::string::npos) line = std::atoi(msg.c_str() + at + 5);
      const auto nl = msg.find('\n');
      if (nl != std::string::npos) msg = msg.substr(nl + 1);
      while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
      while (!msg.empty() && msg.front() == ' ') msg.erase(0, 1);
      fail(path, line, "invalid JSON: " + msg);
    }
    std::vector<std::size_t> line_starts{0};
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts.push_back(i + 1);
    return from_json(root, line_starts);
  }
  if (ext != ".toml") {
    throw Error(ErrorCode::bad_arguments, path + ": a recipe is a .toml or .json file");
  }
  try {
    const toml::table t = toml::parse(text, path);
    Node n = from_toml(t);
    n.line = 1;
    return n;
  } catch (const toml::parse_error& e) {
    fail(path, int(e.source().begin.line), "invalid TOML: " + std::string(e.description()));
  }
}

bool has_glob(const std::string& s) { return s.find_first_of("*?[") != std::string::npos; }

std::vector<std::string> segments(const std::string& p) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= p.size()) {
    const std::size_t slash = p.find('/', start);
    const std::size_t end = slash == std::string::npos ? p.size() : slash;
    if (end > start) out.push_back(p.substr(start, end - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return out;
}

bool match_segments(const std::vector<std::string>& pat, std::size_t i, const std::vector<std::string>& path,
                    std::size_t k) {
  for (; i < pat.size(); ++i, ++k) {
    if (pat[i] == "**") {
      // Any number of folders (hidden ones excepted), none included.
      for (std::size_t skip = k; skip <= path.size(); ++skip) {
        if (match_segments(pat, i + 1, path, skip)) return true;
        if (skip < path.size() && path[skip][0] == '.') return false;
      }
      return false;
    }
    if (k >= path.size() || ::fnmatch(pat[i].c_str(), path[k].c_str(), FNM_PERIOD) != 0) return false;
  }
  return k == path.size();
}

std::string absolute_normal(const std::string& p) {
  std::error_code ec;
  const fs::path a = fs::absolute(p, ec);
  return (ec ? fs::path(p) : a).lexically_normal().string();
}

// The files on disk that match `pattern` (as written relative to the working
// folder or absolute), in the pattern's form: the folder before the first
// segment with a wildcard is walked (recursively only for `**`).
std::vector<std::string> glob_disk(const std::string& pattern) {
  const std::vector<std::string> seg = segments(pattern);
  fs::path root = pattern.size() && pattern[0] == '/' ? fs::path("/") : fs::path();
  std::size_t first = 0;
  while (first < seg.size() && !has_glob(seg[first])) root /= seg[first++];
  std::vector<std::string> out;
  if (first == seg.size()) {
    std::error_code ec;
    if (fs::is_regular_file(root, ec)) out.push_back(root.string());
    return out;
  }
  const bool deep = std::find(seg.begin() + std::ptrdiff_t(first), seg.end(), "**") != seg.end();
  const std::size_t depth = seg.size() - first;
  const std::vector<std::string> rest(seg.begin() + std::ptrdiff_t(first), seg.end());
  std::error_code ec;
  const fs::path start = root.empty() ? fs::path(".") : root;
  if (!fs::is_directory(start, ec)) return out;
  auto consider = [&](const fs::directory_entry& e) {
    std::error_code fe;
    if (!e.is_regular_file(fe)) return;
    const fs::path rel = e.path().lexically_relative(start);
    if (match_segments(rest, 0, segments(rel.string()), 0)) out.push_back((root / rel).string());
  };
  if (deep) {
    for (fs::recursive_directory_iterator it(start, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec)) {
      if (it->path().filename().string()[0] == '.') {
        if (it->is_directory(ec)) it.disable_recursion_pending();
        continue;
      }
      consider(*it);
    }
  } else {
    // Without **, a pattern of N segments names files N folders down.
    std::vector<fs::path> level{start};
    for (std::size_t d = 0; d + 1 < depth; ++d) {
      std::vector<fs::path> next;
      for (const fs::path& dir : level) {
        for (const auto& e : fs::directory_iterator(dir, fs::directory_options::skip_permission_denied, ec)) {
          std::error_code de;
          if (e.is_directory(de) && ::fnmatch(rest[d].c_str(), e.path().filename().c_str(), FNM_PERIOD) == 0) {
            next.push_back(e.path());
          }
        }
      }
      level = std::move(next);
    }
    for (const fs::path& dir : level) {
      for (const auto& e : fs::directory_iterator(dir, fs::directory_options::skip_permission_denied, ec)) consider(e);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string resolve(const fs::path& base, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute() || base.empty()) return p;
  const bool folder = p.back() == '/';
  std::string r = (base / p).lexically_normal().string();
  if (folder && !r.empty() && r.back() != '/') r += '/';
  return r;
}

}  // namespace

bool glob_match(const std::string& pattern, const std::string& path) {
  return match_segments(segments(absolute_normal(pattern)), 0, segments(absolute_normal(path)), 0);
}

namespace {

// `file`, and with --out-dir, for a file under the output folder, its path
// under the recipe's folder.
std::vector<std::string> names_of(const RecipeJob& j, const std::string& file) {
  std::vector<std::string> out{absolute_normal(file)};
  if (!j.output_base.empty()) {
    const fs::path rel = fs::path(out[0]).lexically_relative(j.output_base);
    if (!rel.empty() && *rel.begin() != "..")
      out.push_back((fs::path(j.source_base) / rel).lexically_normal().string());
  }
  return out;
}

}  // namespace

bool excluded(const RecipeJob& j, const std::string& file) {
  for (const std::string& name : names_of(j, file)) {
    for (const std::string& p : j.excludes)
      if (glob_match(p, name)) return true;
  }
  return false;
}

int override_of(const RecipeJob& j, const std::string& file) {
  const std::vector<std::string> names = names_of(j, file);
  for (std::size_t i = 0; i < j.overrides.size(); ++i) {
    for (const std::string& p : j.overrides[i].patterns) {
      for (const std::string& name : names) {
        if (has_glob(p) ? glob_match(p, name) : absolute_normal(p) == name) return int(i);
      }
    }
  }
  return -1;
}

std::vector<std::string> expand_job_inputs(const RecipeJob& j, const std::vector<std::string>& planned,
                                           std::vector<const InputSpec*>* unmatched) {
  std::vector<std::string> out;
  const std::set<std::string> planned_set(planned.begin(), planned.end());
  // The planned output under the output folder that stands in for `f`, or "".
  auto stand_in = [&](const InputSpec& in, const std::string& f) -> std::string {
    if (in.alt.empty()) return "";
    const fs::path rel = fs::path(absolute_normal(f)).lexically_relative(in.base);
    if (rel.empty() || *rel.begin() == "..") return "";
    const std::string alt = (fs::path(in.alt_base) / rel).lexically_normal().string();
    return planned_set.count(alt) ? alt : "";
  };
  for (const InputSpec& in : j.inputs) {
    if (!in.glob) {
      const std::string alt = stand_in(in, in.path);
      out.push_back(alt.empty() ? in.path : alt);
      continue;
    }
    std::vector<std::string> found;
    std::set<std::string> seen;
    for (const std::string& f : glob_disk(in.path)) {
      const std::string alt = stand_in(in, f);
      if (seen.insert(alt.empty() ? absolute_normal(f) : alt).second) found.push_back(alt.empty() ? f : alt);
    }
    for (const std::string& p : planned) {
      if (!seen.count(p) && (glob_match(in.path, p) || (!in.alt.empty() && glob_match(in.alt, p)))) {
        found.push_back(p);
        seen.insert(p);
      }
    }
    std::sort(found.begin(), found.end());
    std::size_t kept = 0;
    for (const std::string& f : found) {
      if (excluded(j, f)) continue;
      out.push_back(f);
      ++kept;
    }
    if (kept == 0 && unmatched) unmatched->push_back(&in);
  }
  return out;
}

std::vector<RecipeOption> merge_options(const std::vector<RecipeOption>& base, const std::vector<RecipeOption>& top) {
  std::vector<RecipeOption> out;
  for (const RecipeOption& o : base) {
    if (std::none_of(top.begin(), top.end(), [&](const RecipeOption& t) { return t.key == o.key; })) out.push_back(o);
  }
  out.insert(out.end(), top.begin(), top.end());
  out.erase(std::remove_if(out.begin(), out.end(), [](const RecipeOption& o) { return o.off; }), out.end());
  return out;
}

std::string where(const Recipe& r, const RecipeJob& j, int line) {
  return r.path + ":" + std::to_string(line ? line : j.line) + ": " +
         (j.name.empty() ? "jobs[" + std::to_string(j.index) + "]" : "job '" + j.name + "'");
}

namespace {

// A table of options (`options`, a `defaults` entry, an override's).
std::vector<RecipeOption> parse_options(const std::string& path, const Node& opts, const std::string& at,
                                        const fs::path& base, const std::string& out_dir) {
  if (opts.kind != Node::table) fail(path, opts.line, at + ": expected a table of option = value");
  std::vector<RecipeOption> out;
  for (const auto& [key, v] : opts.fields) {
    RecipeOption o;
    o.key = key;
    o.line = v.line;
    const std::string ok = at + "." + key;
    switch (v.kind) {
      case Node::boolean:
        o.flag = v.truth;
        o.off = !v.truth;  // a false switch is the default; it removes a default's true
        break;
      case Node::string:
        // Options that name files are paths like inputs and output.
        if (key == "radius-map") {
          o.values.push_back(resolve(base, v.text));
        } else if (key == "preview") {
          o.values.push_back(resolve(out_dir.empty() ? base : fs::path(out_dir), v.text));
        } else {
          o.values.push_back(v.text);
        }
        break;
      case Node::integer:
      case Node::real:
        o.values.push_back(v.text);
        break;
      case Node::array:
        for (const Node& item : v.items) {
          if (item.kind != Node::string && item.kind != Node::integer && item.kind != Node::real) {
            fail(path, item.line, ok + ": expected an array of strings or numbers");
          }
          o.values.push_back(item.text);
        }
        if (o.values.empty()) fail(path, v.line, ok + ": empty array");
        break;
      default:
        fail(path, v.line, ok + ": expected a string, number, boolean or array, found " + kind_name(v.kind));
    }
    out.push_back(std::move(o));
  }
  return out;
}

// A string or a non-empty array of non-empty strings.
std::vector<const Node*> string_list(const std::string& path, const Node& n, const std::string& at) {
  std::vector<const Node*> out;
  if (n.kind == Node::string) {
    out.push_back(&n);
  } else if (n.kind == Node::array && !n.items.empty()) {
    for (const Node& item : n.items) out.push_back(&item);
  } else {
    fail(path, n.line, at + ": expected a string or a non-empty array of strings");
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (out[k]->kind != Node::string || out[k]->text.empty()) {
      fail(path, out[k]->line, at + "[" + std::to_string(k) + "]: expected a non-empty string");
    }
  }
  return out;
}

}  // namespace

Recipe read_recipe(const std::string& path, const std::string& out_dir) {
  const Node root = parse_file(path);
  Recipe r;
  r.path = path;
  const fs::path base = fs::path(path).parent_path();
  for (const auto& [key, v] : root.fields) {
    if (key == "version") {
      if (v.kind != Node::integer || v.text != "1") fail(path, v.line, "version: this texproc reads version 1");
    } else if (key != "jobs" && key != "defaults") {
      fail(path, v.line, key + ": unknown key (valid at the top: version, defaults, jobs)");
    }
  }
  // defaults.COMMAND: options every job of that command starts from.
  std::vector<std::pair<std::string, std::vector<RecipeOption>>> defaults;
  if (const Node* d = root.find("defaults")) {
    if (d->kind != Node::table) fail(path, d->line, "defaults: expected a table of command = { option = value }");
    for (const auto& [command, opts] : d->fields) {
      defaults.emplace_back(command, parse_options(path, opts, "defaults." + command, base, out_dir));
    }
  }
  const Node* jobs = root.find("jobs");
  if (!jobs) fail(path, 1, "jobs: missing (a list of jobs: [[jobs]] in TOML, \"jobs\": [...] in JSON)");
  if (jobs->kind != Node::array || jobs->items.empty())
    fail(path, jobs->line, "jobs: expected a non-empty array of tables");
  for (std::size_t i = 0; i < jobs->items.size(); ++i) {
    const Node& jn = jobs->items[i];
    RecipeJob j;
    j.index = int(i);
    j.line = jn.line;
    const std::string at = "jobs[" + std::to_string(i) + "]";
    if (jn.kind != Node::table) fail(path, jn.line, at + ": expected a table");
    auto string_field = [&](const char* key, bool required, std::string& out, int* line) {
      const Node* n = jn.find(key);
      if (!n) {
        if (required) fail(path, jn.line, at + "." + key + ": missing");
        return;
      }
      if (n->kind != Node::string || n->text.empty()) {
        fail(path, n->line, at + "." + key + ": expected a non-empty string, found " + kind_name(n->kind));
      }
      out = n->text;
      if (line) *line = n->line;
    };
    static const char* known[] = {"name",   "command",   "inputs",  "exclude",
                                  "output", "recursive", "options", "overrides"};
    for (const auto& [key, v] : jn.fields) {
      if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) ==
          std::end(known)) {
        fail(path, v.line,
             at + "." + key +
                 ": unknown key (valid: name, command, inputs, exclude, output, recursive, options, overrides)");
      }
    }
    string_field("name", false, j.name, nullptr);
    string_field("command", true, j.command, &j.command_line);
    string_field("output", true, j.output, &j.output_line);
    j.output = resolve(out_dir.empty() ? base : fs::path(out_dir), j.output);
    if (const Node* rec = jn.find("recursive")) {
      if (rec->kind != Node::boolean) fail(path, rec->line, at + ".recursive: expected true or false");
      j.recursive = rec->truth;
    }
    if (!out_dir.empty()) {
      j.source_base = absolute_normal(base.empty() ? "." : base.string());
      j.output_base = absolute_normal(out_dir);
    }
    const Node* inputs = jn.find("inputs");
    if (!inputs) fail(path, jn.line, at + ".inputs: missing");
    for (const Node* n : string_list(path, *inputs, at + ".inputs")) {
      InputSpec in{n->text, resolve(base, n->text), has_glob(n->text), n->line, "", "", ""};
      if (!out_dir.empty() && !fs::path(n->text).is_absolute()) {
        in.alt = resolve(fs::path(out_dir), n->text);
        in.base = absolute_normal(base.empty() ? "." : base.string());
        in.alt_base = absolute_normal(out_dir);
      }
      j.inputs.push_back(std::move(in));
    }
    if (const Node* ex = jn.find("exclude")) {
      for (const Node* n : string_list(path, *ex, at + ".exclude")) j.excludes.push_back(resolve(base, n->text));
    }
    std::vector<RecipeOption> own;
    if (const Node* opts = jn.find("options")) own = parse_options(path, *opts, at + ".options", base, out_dir);
    const auto d = std::find_if(defaults.begin(), defaults.end(), [&](const auto& e) { return e.first == j.command; });
    j.options = merge_options(d == defaults.end() ? std::vector<RecipeOption>{} : d->second, own);
    if (const Node* ov = jn.find("overrides")) {
      if (ov->kind != Node::array || ov->items.empty()) {
        fail(path, ov->line, at + ".overrides: expected an array of tables ([[jobs.overrides]])");
      }
      for (std::size_t k = 0; k < ov->items.size(); ++k) {
        const Node& on = ov->items[k];
        const std::string ok = at + ".overrides[" + std::to_string(k) + "]";
        if (on.kind != Node::table) fail(path, on.line, ok + ": expected a table with inputs and options");
        RecipeOverride o;
        o.line = on.line;
        for (const auto& [key, v] : on.fields) {
          if (key != "inputs" && key != "options")
            fail(path, v.line, ok + "." + key + ": unknown key (valid: inputs, options)");
        }
        const Node* oi = on.find("inputs");
        const Node* oo = on.find("options");
        if (!oi) fail(path, on.line, ok + ".inputs: missing (the files, or glob patterns, it applies to)");
        if (!oo) fail(path, on.line, ok + ".options: missing");
        for (const Node* n : string_list(path, *oi, ok + ".inputs")) o.patterns.push_back(resolve(base, n->text));
        o.options = parse_options(path, *oo, ok + ".options", base, out_dir);
        j.overrides.push_back(std::move(o));
      }
    }
    r.jobs.push_back(std::move(j));
  }
  return r;
}

}  // namespace texproc::cli
