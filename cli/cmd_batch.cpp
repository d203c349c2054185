// cli/cmd_batch.cpp -- `uniparam batch COMMAND [options] < in.jsonl > out.jsonl`:
// one curve per input line, one JSON result per output line, in order, the
// lines spread over worker threads of one process.
#include <flint/flint.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "output.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/json.hpp"
#include "uniparam/core/parallel.hpp"

namespace uniparam::cli {

namespace {

const char* kBatchHelp =
    "usage: uniparam batch COMMAND [options] < curves.jsonl > results.jsonl\n"
    "\n"
    "Runs COMMAND (uniformity, radical, moebius, reparam, bezier, sample or locate)\n"
    "on every line of standard input, in one process on several threads; writes one\n"
    "JSON object per line, in the order of the input, and a summary on stderr.\n"
    "\n"
    "An input line is a JSON object with one curve:\n"
    "  {\"curve\": \"(t, t^2)\"}\n"
    "  {\"control\": [[0,0],[1,2],[3,1]], \"weights\": [1, \"1/2\", 1]}\n"
    "  {\"svg\": \"M 0 0 Q 1 2 3 1 T 5 0\"}\n"
    "  {\"nurbs\": {\"degree\": 2, \"knots\": [...], \"control\": [...], \"weights\": [...]}}\n"
    "and optionally \"id\" (any JSON value, copied to the result) and \"options\", an\n"
    "object of the command's options for this line ({\"digits\": 20, \"pieces\": 4,\n"
    "\"rational\": true}); they come after the options given on the command line.\n"
    "Numbers are read exactly (decimals as decimals); \"1/3\" may be a string.\n"
    "\n"
    "A result line is {\"line\": N, \"id\": ..., \"status\": 0, \"result\": {...}} with\n"
    "the command's --json answer, or {\"line\": N, \"id\": ..., \"status\": S,\n"
    "\"error\": {\"type\": ..., \"message\": ...}} (S as the command's exit code: 2\n"
    "invalid input, 3 domain error, 4 budget or time); a command that printed a\n"
    "warning (a missed --target) adds \"warning\". A bad line never stops the batch.\n"
    "Blank lines are skipped (their numbers still count).\n"
    "\n"
    "options of batch itself:\n"
    "  --jobs N      lines computed at once (default: UNIPARAM_THREADS, else the cores, at most 8)\n"
    "  --timeout S   time limit of each line in seconds (default 600)\n"
    "  --progress    progress on stderr (default: when stderr is a terminal)\n"
    "  --no-progress no progress\n"
    "every other option goes to COMMAND for every line (e.g. --speed parametric).\n"
    "\n"
    "Exit status: 0 when every line has a result; otherwise the largest line status;\n"
    "1 when the output cannot be written.\n";

// `text` (JSON as a command prints it) without whitespace outside strings.
std::string compact(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false, escaped = false;
  for (char ch : text) {
    if (in_string) {
      out += ch;
      if (escaped) escaped = false;
      else if (ch == '\\') escaped = true;
      else if (ch == '"') in_string = false;
    } else if (ch == '"') {
      in_string = true;
      out += ch;
    } else if (ch != ' ' && ch != '\n' && ch != '\t' && ch != '\r') {
      out += ch;
    }
  }
  return out;
}

// A JSON number or string entry of a point list as exact rational text.
std::string rational_text(const JsonValue& v, const std::string& what) { return v.as_rational(what).str(); }

// [[x, y], ...] or [w, ...] as the text --control / --weights read.
std::string list_text(const JsonValue& v, const std::string& key) {
  if (v.is_string()) return v.text;
  std::string s = "[";
  const auto& items = v.as_array("\"" + key + "\"");
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) s += ",";
    const std::string what = key + " entry " + std::to_string(i);
    if (items[i].is_array()) {
      s += "[";
      const auto& xs = items[i].as_array(what);
      for (std::size_t k = 0; k < xs.size(); ++k) s += (k ? "," : "") + rational_text(xs[k], what);
      s += "]";
    } else {
      s += rational_text(items[i], what);
    }
  }
  return s + "]";
}

// The arguments of one line's command: curve and per-line options.
std::vector<std::string> line_arguments(const JsonValue& j, std::string& id) {
  if (!j.is_object()) throw InvalidArgument(std::string("a line must be a JSON object, got ") + j.kind_name());
  std::vector<std::string> args;
  int curves = 0;
  for (const auto& [key, v] : j.as_object("the line")) {
    if (key == "id") {
      id = v.dump();
    } else if (key == "curve") {
      args.insert(args.begin(), v.as_string("\"curve\""));
      ++curves;
    } else if (key == "control" || key == "weights") {
      args.push_back("--" + key);
      args.push_back(list_text(v, key));
      curves += key == "control";
    } else if (key == "svg") {
      args.push_back("--svg");
      args.push_back(v.as_string("\"svg\""));
      ++curves;
    } else if (key == "nurbs") {
      args.push_back("--nurbs");
      args.push_back(v.is_string() ? v.text : v.dump());
      ++curves;
    } else if (key == "options") {
      for (const auto& [name, o] : v.as_object("\"options\"")) {
        if (name == "help" || name == "output" || name == "threads" || name == "timeout")
          throw InvalidArgument("option \"" + name + "\" is not available per line in a batch");
        if (o.is_bool()) {
          if (o.boolean) args.push_back("--" + name);
        } else if (o.is_number() || o.is_string()) {
          args.push_back("--" + name);
          args.push_back(o.text);
        } else {
          throw InvalidArgument("option \"" + name + "\" must be a string, a number or a boolean, got " +
                                o.kind_name());
        }
      }
    } else {
      throw InvalidArgument("unknown key \"" + key +
                            "\" (expected curve, control, weights, svg, nurbs, options or id)");
    }
  }
  if (curves != 1)
    throw InvalidArgument(curves ? "a line must give one curve (curve, control, svg or nurbs), it gives " +
                                       std::to_string(curves)
                                 : "the line gives no curve (curve, control, svg or nurbs)");
  return args;
}

struct LineResult {
  int status = 0;
  std::string json;  // the whole output line
};

LineResult run_line(const Command& cmd, const std::vector<std::string>& common, long number, const std::string& text,
                    double seconds) {
  std::string id;
  std::ostringstream answer_buf, warn_buf;
  auto finish = [&](int status, const std::string& body) {
    std::string s = "{\"line\":" + std::to_string(number);
    if (!id.empty()) s += ",\"id\":" + id;
    s += ",\"status\":" + std::to_string(status) + "," + body;
    const std::string w = warn_buf.str();
    if (!w.empty()) s += ",\"warning\":" + json_quote(w.substr(0, w.find_last_not_of('\n') + 1));
    return LineResult{status, s + "}"};
  };
  auto error = [&](const char* type, const std::string& message, int status) {
    return finish(status, std::string("\"error\":{\"type\":\"") + type + "\",\"message\":" + json_quote(message) + "}");
  };
  try {
    const JsonValue j = parse_json(text);
    std::vector<std::string> args{"uniparam", cmd.spec.name};
    const std::vector<std::string> own = line_arguments(j, id);
    std::size_t first_option = 0;
    if (!own.empty() && own.front().rfind("--", 0) != 0) args.push_back(own.front()), first_option = 1;
    for (const std::string& c : common) args.push_back(c);
    for (std::size_t i = first_option; i < own.size(); ++i) args.push_back(own[i]);
    args.push_back("--json");
    std::vector<char*> argv;
    for (std::string& s : args) argv.push_back(s.data());
    const ThreadOutput to(answer_buf, warn_buf);
    const TimeBudget budget(seconds);
    const int status = cmd.run(static_cast<int>(argv.size()), argv.data());
    return finish(status, "\"result\":" + compact(answer_buf.str()));
  } catch (const ParseError& e) {
    return error("ParseError", e.what(), 2);
  } catch (const InvalidArgument& e) {
    return error("InvalidArgument", e.what(), 2);
  } catch (const DomainError& e) {
    return error("DomainError", e.what(), 3);
  } catch (const TimeLimitExceeded& e) {
    return error("TimeLimitExceeded", e.what(), 4);
  } catch (const BudgetExceeded& e) {
    return error("BudgetExceeded", e.what(), 4);
  } catch (const std::bad_alloc&) {
    return error("Error", "out of memory", 1);
  } catch (const std::exception& e) {
    return error("Error", std::string("internal error: ") + e.what(), 1);
  }
}

}  // namespace

int run_batch(int argc, char** argv) {
  if (argc < 3 || !std::string(argv[2]).compare("--help") || !std::string(argv[2]).compare("-h")) {
    (argc < 3 ? warn() : answer()) << kBatchHelp;
    return argc < 3 ? 2 : 0;
  }
  const std::string name = argv[2];
  const Command* cmd = nullptr;
  for (const auto& c : commands())
    if (c.spec.name == name) cmd = &c;
  if (!cmd || name == "plot")
    throw InvalidArgument("batch runs uniformity, radical, moebius, reparam, bezier, sample or locate, not '" + name +
                          "'");
  long jobs = static_cast<long>(worker_count());
  double seconds = 600;
  int progress = isatty(2) ? 1 : 0;
  std::vector<std::string> common;
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InvalidArgument("option '" + arg + "' needs a value");
      return argv[++i];
    };
    if (arg == "--jobs") jobs = parse_long("--jobs", value(), 1, 64);
    else if (arg == "--timeout") {
      Args t;
      t.values["timeout"] = value();
      seconds = read_timeout(t);
    } else if (arg == "--progress") progress = 1;
    else if (arg == "--no-progress") progress = 0;
    else if (arg == "--help" || arg == "-h" || arg == "--output" || arg == "-o" || arg == "--threads")
      throw InvalidArgument("option '" + arg + "' is not available in a batch (see 'uniparam batch --help')");
    else common.push_back(arg);
  }
  // The command-line options are checked once, on a curve of no
  // consequence, so that a mistake there is one error, not one per line.
  {
    std::vector<std::string> probe{"uniparam", name};
    for (const std::string& c : common) probe.push_back(c);
    probe.push_back("--help");
    std::vector<char*> pv;
    for (std::string& s : probe) pv.push_back(s.data());
    Args parsed = parse_args(cmd->spec, static_cast<int>(pv.size()), pv.data(), 2);
    for (const char* o : {"control", "svg", "nurbs", "weights"})
      if (parsed.has(o)) throw InvalidArgument(std::string("--") + o + " belongs in the input lines, not on the command line");
  }

  stream_stdout();  // results go out chunk by chunk
  std::ostream& out = answer();
  const auto start = std::chrono::steady_clock::now();
  long number = 0, done = 0, failed = 0;
  int worst = 0;
  const std::size_t chunk = static_cast<std::size_t>(std::max(64L, 16 * jobs));
  std::string text;
  bool eof = false;
  auto last_progress = start;
  while (!eof) {
    std::vector<std::pair<long, std::string>> lines;
    while (lines.size() < chunk) {
      if (!std::getline(std::cin, text)) {
        eof = true;
        break;
      }
      ++number;
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      lines.emplace_back(number, text);
    }
    std::vector<LineResult> results(lines.size());
    std::atomic<std::size_t> next{0};
    auto work = [&]() {
      for (std::size_t i; (i = next++) < lines.size();)
        results[i] = run_line(*cmd, common, lines[i].first, lines[i].second, seconds);
    };
    std::vector<std::thread> pool;
    const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(jobs), lines.size());
    for (std::size_t k = 1; k < n; ++k)
      pool.emplace_back([&work] {
        work();
        flint_cleanup();  // this thread's FLINT/Arb caches
      });
    work();
    for (auto& t : pool) t.join();
    for (const LineResult& r : results) {
      out << r.json << "\n";
      ++done;
      if (r.status != 0) ++failed, worst = std::max(worst, r.status);
    }
    out.flush();
    if (!out) {
      const std::string why = stdout_stream_error();
      warn() << "uniparam batch: cannot write the output to stdout" << (why.empty() ? "" : ": " + why) << " ("
             << done << " results handed over)\n";
      return 1;
    }
    const auto now = std::chrono::steady_clock::now();
    if (progress && now - last_progress > std::chrono::milliseconds(500)) {
      warn() << "\runiparam batch: " << done << " lines, " << failed << " failed" << std::flush;
      last_progress = now;
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.3g s, %.0f lines/s", secs, secs > 0 ? done / secs : 0.0);
  warn() << (progress ? "\r" : "") << "uniparam batch " << name << ": " << done << " lines, " << done - failed
         << " ok, " << failed << " failed (" << rate << ")\n";
  return worst;
}

}  // namespace uniparam::cli
