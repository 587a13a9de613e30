// `fixstep new DIR`: writes a standalone prototype project (CMakeLists.txt, main.cpp,
// scene.toml, README.md) built against the installed fixstep package. The files are those of
// cli/template/, embedded in the program at build time (template_files.cpp.in).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace fixstep::cli {

/// One file of the project template: its name in the new project and its text, in which
/// "@NAME@" stands for the project's name and "@VERSION@" for fixstep's MAJOR.MINOR.
struct TemplateFile {
  std::string_view name;
  std::string_view text;
};
/// The template's files, embedded at build time (generated from template_files.cpp.in).
[[nodiscard]] std::span<const TemplateFile> template_files();
/// fixstep's version as MAJOR.MINOR: what the project's find_package asks for.
[[nodiscard]] std::string_view template_version();
/// CMAKE_INSTALL_LIBDIR of this build (where the package config is installed, under the prefix).
[[nodiscard]] std::string_view install_libdir();

/// The project's name for directory `dir`: its last component, every character other than a
/// letter, digit or '_' replaced by '_', with '_' before a leading digit (a valid CMake target
/// and C identifier: "my-game" gives "my_game"). Throws std::invalid_argument ("DIR is empty
/// ...", "DIR '..' has no name of its own ...") for a path without a last component ("", "/",
/// "..", "a/..").
[[nodiscard]] std::string project_name(const std::filesystem::path& dir);

/// `text` with every "@NAME@" replaced by `name` and every "@VERSION@" by `version`.
[[nodiscard]] std::string fill_template(std::string_view text, std::string_view name,
                                        std::string_view version);

/// `word` as one word for a POSIX shell: as it is when it holds only letters, digits and
/// _./:@%+=,- ; else in single quotes (a quote inside as '\''). "./" first when it starts
/// with '-', so that `cd` does not read it as an option. "my game" gives 'my game'.
[[nodiscard]] std::string shell_quoted(std::string_view word);

/// `fixstep new DIR`: writes the project whole or not at all: into a temporary directory
/// beside DIR (StagedDirectory, missing parents created), renamed onto DIR once every file is
/// written; a write error (a full disk, `ulimit -f`), an exception or a stop request (SIGINT,
/// SIGTERM: StopRequested) removes it and the parents it created. Then prints how to build and
/// run it, DIR quoted for the shell. A symbolic link DIR is followed. Refuses, writing
/// nothing: an unusable DIR ("", "/", "..": PathRefused naming it, exit 2), a DIR that is not
/// a directory or a directory that is not empty (std::runtime_error). Throws
/// std::runtime_error naming the directory (or file) and the system's reason when it cannot
/// create or write them. Returns the exit status (0).
int new_command(const std::string& dir);

}  // namespace fixstep::cli
