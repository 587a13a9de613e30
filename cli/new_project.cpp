// fixstep new DIR: a prototype project from the template embedded in the program.
#include "new_project.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/io/output_target.hpp>
#include <fixstep/io/stop_signal.hpp>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "output_paths.hpp"
#include "staged_directory.hpp"

namespace fixstep::cli {

namespace fs = std::filesystem;

namespace {

bool identifier_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

/// Throws unless `dir` is missing or an empty directory: a project is written only there.
void check_target(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status)) {
    throw std::runtime_error(fmt::format(
        "{} exists and is not a directory: fixstep new writes a project into a new or empty "
        "directory",
        dir.string()));
  }
  const fs::directory_iterator entries(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot read {}: {}", dir.string(), ec.message()));
  if (entries != fs::directory_iterator()) {
    throw std::runtime_error(fmt::format(
        "{} is not empty: fixstep new writes a project only into a new or empty directory and "
        "overwrites nothing (nothing was written; give a new directory)",
        dir.string()));
  }
}

/// Writes `text` into `file`, which must not exist (opened exclusively: never overwritten).
/// Errors name `shown`: the file's name once in place.
void write_new_file(const fs::path& file, std::string_view text, const fs::path& shown) {
  std::FILE* out = std::fopen(file.c_str(), "wx");
  if (out == nullptr) {
    throw std::runtime_error(
        fmt::format("cannot create {}: {}", shown.string(),
                    std::error_code(errno, std::generic_category()).message()));
  }
  // The bytes reach the file at the flush (a full disk, `ulimit -f`: ENOSPC, EFBIG): the error
  // reported is the errno of the call that failed, taken before any other call can change it.
  errno = 0;
  int err = 0;
  if (std::fwrite(text.data(), 1, text.size(), out) != text.size() || std::fflush(out) != 0) {
    err = errno != 0 ? errno : EIO;
  }
  errno = 0;
  if (std::fclose(out) != 0 && err == 0) err = errno != 0 ? errno : EIO;
  if (err != 0) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", shown.string(),
                                         std::error_code(err, std::generic_category()).message()));
  }
}

/// Whether `bin` is one of the directories of the PATH environment variable (CMake's
/// find_package searches the prefix above each of them).
bool on_path(const fs::path& bin) {
  const char* path = std::getenv("PATH");
  std::string_view rest = path != nullptr ? path : "";
  while (!rest.empty()) {
    const std::size_t colon = std::min(rest.find(':'), rest.size());
    std::error_code ec;
    if (colon > 0 && fs::equivalent(fs::path(rest.substr(0, colon)), bin, ec)) return true;
    rest.remove_prefix(std::min(colon + 1, rest.size()));
  }
  return false;
}

/// How the new project's `cmake -B build` finds this fixstep: "" when the installed package
/// is beside this program and its bin directory is on PATH, " -DCMAKE_PREFIX_PATH=P" when it
/// is installed in P but not on PATH, nullopt when this program is not an installed one.
std::optional<std::string> cmake_prefix_argument() {
  std::error_code ec;
  const fs::path bin = fs::read_symlink("/proc/self/exe", ec).parent_path();
  const fs::path prefix = bin.parent_path();
  if (ec || !fs::exists(prefix / install_libdir() / "cmake/fixstep/fixstepConfig.cmake", ec)) {
    return std::nullopt;
  }
  if (on_path(bin)) return std::string();
  return fmt::format(" -DCMAKE_PREFIX_PATH={}", prefix.string());
}

/// What to type next.
void print_next_steps(const std::string& dir, const std::string& name) {
  const std::string quoted = shell_quoted(dir);
  const std::optional<std::string> prefix = cmake_prefix_argument();
  std::printf(
      "Build and run it (its README.md says more):\n"
      "  cd %s\n"
      "  cmake -B build%s && cmake --build build\n"
      "  ./build/%s                              play in a window\n"
      "  ./build/%s --frames 120 --out frames    or 120 frames headless, as PNGs\n",
      quoted.c_str(), prefix.value_or("").c_str(), name.c_str(), name.c_str());
  if (!prefix) {
    std::printf(
        "note: this fixstep is not an installed one: install the package first (cmake --install "
        "BUILD_DIR --prefix P) and add -DCMAKE_PREFIX_PATH=P to the first cmake\n");
  }
}

}  // namespace

std::string shell_quoted(std::string_view word) {
  constexpr std::string_view safe =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./:@%+=,-";
  const std::string head = word.starts_with('-') ? "./" : "";  // not read as an option
  if (!word.empty() && word.find_first_not_of(safe) == std::string_view::npos) {
    return head + std::string(word);
  }
  std::string out = head + "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string project_name(const fs::path& dir) {
  if (dir.empty()) {
    throw std::invalid_argument(
        "DIR is empty (\"\"): give the project's directory, such as games/grabber");
  }
  fs::path path = fs::absolute(dir).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();  // "game/" names "game"
  const std::string last = path.filename().string();
  if (last.empty() || last == "." || last == "..") {
    throw std::invalid_argument(
        fmt::format("DIR {} has no name of its own: a project needs a directory with a name, "
                    "such as games/grabber",
                    shell_quoted(dir.string())));
  }
  std::string name = last[0] >= '0' && last[0] <= '9' ? "_" : "";
  for (const char c : last) name += identifier_char(c) ? c : '_';
  return name;
}

std::string fill_template(std::string_view text, std::string_view name, std::string_view version) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    if (text.substr(i).starts_with("@NAME@")) {
      out += name;
      i += 6;
    } else if (text.substr(i).starts_with("@VERSION@")) {
      out += version;
      i += 9;
    } else {
      out += text[i++];
    }
  }
  return out;
}

namespace {
/// The directory a project named `dir` goes to: a symbolic link's final target.
fs::path project_target(const std::string& dir) {
  const OutputTarget target = classify_output(dir);
  return target.fd < 0 && target.kind != OutputKind::stream ? target.path : fs::path(dir);
}

/// The template's files written into `into`; a stop request (SIGINT, SIGTERM) between two
/// files throws StopRequested. Errors name the files as in `dir`. Returns their names, for
/// the summary.
std::string write_project(const fs::path& into, const std::string& dir, const std::string& name) {
  std::string written;
  for (const TemplateFile& file : template_files()) {
    throw_if_stop_requested();
    write_new_file(into / file.name, fill_template(file.text, name, template_version()),
                   fs::path(dir) / file.name);
    written += fmt::format(" {}", file.name);
  }
  throw_if_stop_requested();
  return written;
}
}  // namespace

int new_command(const std::string& dir) {
  std::string name;
  try {
    name = project_name(dir);
  } catch (const std::invalid_argument& e) {
    throw PathRefused(fmt::format("fixstep new: {}", e.what()));
  }
  const fs::path target = project_target(dir);
  check_target(target);
  const StopOnSignal signals;  // a stop request removes the half-made project
  std::string written;
  try {
    StagedDirectory staged(target);
    written = write_project(staged.path(), dir, name);
    staged.publish();
  } catch (const StopRequested&) {
    throw;
  } catch (const std::runtime_error& e) {  // StagedDirectory removed what it made
    throw std::runtime_error(fmt::format("{} (fixstep new left nothing behind)", e.what()));
  }
  std::printf("fixstep new: wrote the project '%s' into %s:%s\n", name.c_str(),
              shell_quoted(dir).c_str(), written.c_str());
  print_next_steps(dir, name);
  return 0;
}

}  // namespace fixstep::cli
