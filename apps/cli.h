#pragma once
// The rbcflow command line: each subcommand parses its arguments and calls the library.
// Exit status (docs/case-format.md): 0 success, 2 bad case file or argument, 1 failure in a run.
#include <stdexcept>
#include <string>
#include <vector>

namespace rbcflow::cli {

// A bad argument or input file: the message names it; exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Arguments after the subcommand name, consumed as they are parsed.
class Args {
 public:
  Args(std::string command, std::vector<std::string> args);
  bool flag(const std::string& name);                    // --name
  bool option(const std::string& name, std::string& v);  // --name VALUE (or -o VALUE)
  std::string positional(const std::string& what);       // next non-option, required
  std::string next_positional();                         // next non-option, or empty
  bool help_requested() const;
  void finish() const;  // anything left over is an error

 private:
  std::string command_;
  std::vector<std::string> args_;
};

// `text` as an integer in [1, max]; else UsageError "rbcflow COMMAND: OPTION must be ...".
long positive_integer(const std::string& command, const std::string& option, const std::string& text, long max);

int run_info(Args& args);
int run_shape(Args& args);
int run_check(Args& args);
int run_render(Args& args);
int run_run(Args& args);
int run_mesh(Args& args);
int run_study(Args& args);

}  // namespace rbcflow::cli
