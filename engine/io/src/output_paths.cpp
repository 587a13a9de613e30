// The checks of a program's paths before any work (fixstep/io/output_paths.hpp).
#include "fixstep/io/output_paths.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "fixstep/io/capture_files.hpp"
#include "fixstep/io/output_target.hpp"
#include "fixstep/io/stale_temporaries.hpp"

namespace fixstep {

namespace {

/// A file's identity: device and inode; for a file not there yet, its absolute path with every
/// existing directory in it resolved (symbolic links, "..", "."), device and inode 0.
struct FileId {
  dev_t dev = 0;
  ino_t ino = 0;
  std::string path;        ///< "" for an existing file
  std::string stream;      ///< what a stream is ("standard output", "a FIFO (named pipe)"), or ""
  bool shareable = false;  ///< a character device named by its path (/dev/null), not stdout
  bool operator==(const FileId& o) const { return dev == o.dev && ino == o.ino && path == o.path; }
};

std::filesystem::path resolved(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec).lexically_normal();
  std::filesystem::path p = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute : p;
}

/// The identity of an input (`may_be_new` false) or an output: what the output's name stands
/// for (classify_output), so "-" and "/dev/stdout" are standard output, not files so named.
std::optional<FileId> id_of(const std::string& path, bool may_be_new) {
  struct stat st {};
  const OutputTarget target = may_be_new ? classify_output(path) : OutputTarget{};
  const std::string stream = target.kind == OutputKind::stream ? target.what : "";
  if (target.fd >= 0) {
    if (::fstat(target.fd, &st) != 0) return std::nullopt;  // not open: refuse_kinds says so
    return FileId{st.st_dev, st.st_ino, "", stream, false};
  }
  if (::stat(path.c_str(), &st) == 0) {
    return FileId{st.st_dev, st.st_ino, "", stream, may_be_new && S_ISCHR(st.st_mode)};
  }
  if (!may_be_new) return std::nullopt;
  return FileId{0, 0, resolved(path).string(), "", false};
}

std::string named(const NamedPath& p) {
  return fmt::format("{} {}", p.role, p.path);
}

[[noreturn]] void refuse_input(const OutputPaths& c, const NamedPath& out, const NamedPath& in) {
  throw PathRefused(
      fmt::format("{}: {} is the same file as {}: an output may never overwrite an input (nothing "
                  "was written); give another path",
                  c.program, named(out), named(in)));
}

/// An input that is a capture file already in the capture directory (rewritten or removed).
void refuse_capture_inputs(const OutputPaths& c,
                           const std::vector<std::pair<NamedPath, FileId>>& inputs) {
  if (!c.capture_dir) return;
  for (const auto& f : capture_files_in(*c.capture_dir)) {
    const auto id = id_of(f.string(), false);
    for (const auto& [in, in_id] : inputs) {
      if (id && *id == in_id) refuse_input(c, {"--out's old capture file", f.string()}, in);
    }
  }
}

/// A file given for another output that the capture in `capture_dir` would write: DIR/frame_N.png.
void refuse_capture_names(const OutputPaths& c, const NamedPath& out) {
  const std::filesystem::path p = resolved(out.path);
  const std::string name = p.filename().string();
  // compare --csv DIR/compare.csv names the summary's default place: not a clash.
  if (!c.capture_dir || out.role.starts_with("--out") || !is_capture_file(name) ||
      (name == "compare.csv" && out.role == "--csv")) {
    return;
  }
  if (p.parent_path() == resolved(*c.capture_dir)) {
    throw PathRefused(
        fmt::format("{}: {} is a file the capture in --out {} writes: one output would overwrite "
                    "the other (nothing was written); give each its own path",
                    c.program, named(out), *c.capture_dir));
  }
}

void refuse_same_files(const OutputPaths& c) {
  std::vector<std::pair<NamedPath, FileId>> seen;
  for (const NamedPath& in : c.inputs) {
    if (const auto id = id_of(in.path, false)) seen.emplace_back(in, *id);
  }
  refuse_capture_inputs(c, seen);
  const std::size_t inputs = seen.size();
  for (const NamedPath& out : c.outputs) {
    const auto id = id_of(out.path, true);
    if (!id) continue;
    for (std::size_t i = 0; i < seen.size(); ++i) {
      // Two outputs streaming into one character device (--csv /dev/null --record /dev/null)
      // do no harm; into one file, FIFO or standard output they would mix or overwrite.
      if (seen[i].second != *id || (i >= inputs && id->shareable && seen[i].second.shareable)) {
        continue;
      }
      if (i < inputs) refuse_input(c, out, seen[i].first);
      if (!id->stream.empty()) {
        throw PathRefused(
            fmt::format("{}: {} and {} both write into {}: their bytes would be mixed (nothing was "
                        "written); give each its own path",
                        c.program, named(seen[i].first), named(out), id->stream));
      }
      throw PathRefused(
          fmt::format("{}: {} and {} are the same file: one output would overwrite the other "
                      "(nothing was written); give each its own path",
                      c.program, named(seen[i].first), named(out)));
    }
    refuse_capture_names(c, out);
    seen.emplace_back(out, *id);
  }
}

/// "" when descriptor `fd` is open for writing, else why not.
std::string descriptor_refusal(int fd, const std::string& what) {
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0) return fmt::format("names {}, which is not open", what);
  if ((flags & O_ACCMODE) == O_RDONLY) return fmt::format("names {}, open for reading only", what);
  return {};
}

/// An output that is a directory, block device, socket or other special file, or names a
/// descriptor that is not open for writing.
void refuse_kinds(const OutputPaths& c) {
  for (const NamedPath& out : c.outputs) {
    const OutputTarget target = classify_output(out.path);
    std::string why = output_refusal(target);
    if (why.empty() && target.fd >= 0) why = descriptor_refusal(target.fd, target.what);
    if (!why.empty()) {
      throw PathRefused(fmt::format("{}: {} {}; nothing was written", c.program, named(out), why));
    }
  }
}

}  // namespace

void check_output_paths(const OutputPaths& c) {
  refuse_kinds(c);
  refuse_same_files(c);
  if (c.capture_dir) {
    if (const std::string e = capture_dir_refusal(*c.capture_dir, c.overwrite); !e.empty()) {
      throw PathRefused(fmt::format("{}: {}", c.program, e));
    }
  }
  for (const NamedPath& out : c.outputs) {  // beside the file replaced: links followed
    const OutputTarget target = classify_output(out.path);
    if (target.kind != OutputKind::file) continue;
    const std::string name = target.path.filename().string();
    remove_stale_temporaries(target.path.parent_path(),
                             [&](std::string_view t) { return t == name; });
  }
}

std::optional<std::string> naming_the_option(const OutputPaths& c, std::string_view message) {
  constexpr std::string_view head = "cannot write ";
  if (!message.starts_with(head)) return std::nullopt;
  const std::string_view rest = message.substr(head.size());
  for (const NamedPath& out : c.outputs) {
    if (rest.starts_with(out.path + ":")) return fmt::format("{}: {}", out.role, message);
  }
  if (c.capture_dir && rest.starts_with((std::filesystem::path(*c.capture_dir) / "").string())) {
    return fmt::format("--out: {}", message);
  }
  return std::nullopt;
}

namespace {
/// Whether `target` (a stream opened by path) is the file descriptor 1 is open on.
bool same_as_descriptor_1(const OutputTarget& target) {
  struct stat out {
  }, st{};
  return ::fstat(1, &out) == 0 && ::stat(target.path.c_str(), &st) == 0 &&
         (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) && st.st_dev == out.st_dev &&
         st.st_ino == out.st_ino;
}
}  // namespace

bool data_on_standard_output(const OutputPaths& paths) {
  for (const NamedPath& out : paths.outputs) {
    const OutputTarget target = classify_output(out.path);
    if (target.kind != OutputKind::stream) continue;
    if (target.fd == standard_output_descriptor()) return true;
    if (target.fd < 0 && same_as_descriptor_1(target)) return true;
  }
  return false;
}

void keep_standard_output_for_data() {
  std::fflush(stdout);
  const int data = ::fcntl(1, F_DUPFD_CLOEXEC, 10);
  if (data < 0) return;  // not open: the data's writer reports it
  set_standard_output_descriptor(data);
  ::dup2(2, 1);
}

}  // namespace fixstep
