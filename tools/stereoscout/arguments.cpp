#include "arguments.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>

namespace stereoscout::cli {

Arguments::Arguments(std::string command, std::string summary)
    : command_(std::move(command)), summary_(std::move(summary)) {}

void Arguments::option(const std::string& name, const std::string& value_name, const std::string& help,
                       const std::string& default_value) {
  Entry entry;
  entry.name = name;
  entry.value_name = value_name;
  entry.help = help;
  entry.default_value = default_value;
  entries_.push_back(entry);
}

void Arguments::flag(const std::string& name, const std::string& help) {
  Entry entry;
  entry.name = name;
  entry.help = help;
  entry.is_flag = true;
  entries_.push_back(entry);
}

void Arguments::positional(const std::string& name, const std::string& help, bool required) {
  Entry entry;
  entry.name = name;
  entry.help = help;
  entry.is_positional = true;
  entry.required = required;
  entries_.push_back(entry);
}

Arguments::Entry* Arguments::find(const std::string& name) {
  for (Entry& entry : entries_) {
    if (entry.name == name) {
      return &entry;
    }
  }
  return nullptr;
}

const Arguments::Entry* Arguments::find(const std::string& name) const {
  return const_cast<Arguments*>(this)->find(name);
}

bool Arguments::parse(int argc, char** argv) {
  auto fail = [this](const std::string& message) {
    std::fprintf(stderr, "stereoscout %s: %s\n(see stereoscout %s --help)\n", command_.c_str(), message.c_str(),
                 command_.c_str());
    exit_code_ = 2;
    return false;
  };
  std::size_t next_positional = 0;
  for (int i = 0; i < argc; ++i) {
    const std::string word = argv[i];
    if (word == "--help" || word == "-h") {
      std::fputs(help_text().c_str(), stdout);
      exit_code_ = 0;
      return false;
    }
    if (word.rfind("--", 0) == 0) {
      std::string name = word.substr(2);
      std::string value;
      const std::size_t equals = name.find('=');
      const bool inline_value = equals != std::string::npos;
      if (inline_value) {
        value = name.substr(equals + 1);
        name = name.substr(0, equals);
      }
      Entry* entry = find(name);
      if (entry == nullptr || entry->is_positional) {
        return fail("unknown option --" + name);
      }
      if (entry->is_flag) {
        if (inline_value) {
          return fail("--" + name + " takes no value");
        }
        entry->given = true;
        continue;
      }
      if (!inline_value) {
        if (i + 1 >= argc) {
          return fail("--" + name + " needs a value (" + entry->value_name + ")");
        }
        value = argv[++i];
      }
      entry->given = true;
      entry->value = value;
      continue;
    }
    std::size_t seen = 0;
    Entry* target = nullptr;
    for (Entry& entry : entries_) {
      if (entry.is_positional && seen++ == next_positional) {
        target = &entry;
        break;
      }
    }
    if (target == nullptr) {
      return fail("unexpected argument '" + word + "'");
    }
    target->given = true;
    target->value = word;
    ++next_positional;
  }
  for (const Entry& entry : entries_) {
    if (entry.is_positional && entry.required && !entry.given) {
      return fail("missing " + entry.name);
    }
  }
  return true;
}

bool Arguments::has(const std::string& name) const {
  const Entry* entry = find(name);
  return entry != nullptr && entry->given;
}

std::string Arguments::get(const std::string& name) const {
  const Entry* entry = find(name);
  if (entry == nullptr) {
    return "";
  }
  return entry->given ? entry->value : entry->default_value;
}

bool Arguments::get_int(const std::string& name, long long& value) const {
  const std::string text = get(name);
  char* end = nullptr;
  errno = 0;
  const long long parsed = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0) {
    std::fprintf(stderr, "stereoscout %s: --%s expects an integer, got '%s'\n", command_.c_str(), name.c_str(),
                 text.c_str());
    return false;
  }
  value = parsed;
  return true;
}

bool Arguments::get_double(const std::string& name, double& value) const {
  const std::string text = get(name);
  char* end = nullptr;
  errno = 0;
  const double parsed = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno != 0) {
    std::fprintf(stderr, "stereoscout %s: --%s expects a number, got '%s'\n", command_.c_str(), name.c_str(),
                 text.c_str());
    return false;
  }
  value = parsed;
  return true;
}

std::string Arguments::help_text() const {
  std::string usage = "usage: stereoscout " + command_;
  std::string details;
  for (const Entry& entry : entries_) {
    std::string left;
    if (entry.is_positional) {
      usage += entry.required ? " " + entry.name : " [" + entry.name + "]";
      left = entry.name;
    } else if (entry.is_flag) {
      usage += " [--" + entry.name + "]";
      left = "--" + entry.name;
    } else {
      usage += " [--" + entry.name + " " + entry.value_name + "]";
      left = "--" + entry.name + " " + entry.value_name;
    }
    std::string line = "  " + left;
    line.append(left.size() < 26 ? 28 - line.size() : 1, ' ');
    line += entry.help;
    if (!entry.default_value.empty()) {
      line += " (default: " + entry.default_value + ")";
    }
    details += line + "\n";
  }
  return usage + "\n\n" + summary_ + "\n\n" + details + "  --help                    this text\n";
}

}  // namespace stereoscout::cli
