#pragma once
// A small command-line parser for the subcommands: --name value options, --flag switches,
// positional arguments, and a --help text made from the declarations.

#include <string>
#include <vector>

namespace stereoscout::cli {

class Arguments {
 public:
  Arguments(std::string command, std::string summary);

  // Declarations, made before parse().
  void option(const std::string& name, const std::string& value_name, const std::string& help,
              const std::string& default_value = "");
  void flag(const std::string& name, const std::string& help);
  void positional(const std::string& name, const std::string& help, bool required = true);

  // Parses argv after the subcommand name. Returns false on --help (help printed to stdout,
  // exit code 0) or on an error (message on stderr, exit code 2); see exit_code().
  bool parse(int argc, char** argv);
  int exit_code() const { return exit_code_; }

  bool has(const std::string& name) const;  // option given on the command line, or flag set
  std::string get(const std::string& name) const;  // option value or its default, positional value
  // Numeric value; on a malformed number prints an error naming the option and returns false.
  bool get_int(const std::string& name, long long& value) const;
  bool get_double(const std::string& name, double& value) const;

  std::string help_text() const;

 private:
  struct Entry {
    std::string name;
    std::string value_name;
    std::string help;
    std::string default_value;
    bool is_flag = false;
    bool is_positional = false;
    bool required = false;
    bool given = false;
    std::string value;
  };
  Entry* find(const std::string& name);
  const Entry* find(const std::string& name) const;

  std::string command_;
  std::string summary_;
  std::vector<Entry> entries_;
  int exit_code_ = 0;
};

}  // namespace stereoscout::cli
