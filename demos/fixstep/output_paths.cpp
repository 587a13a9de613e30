#include "output_paths.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <filesystem>
#include <fixstep/manifest.hpp>
#include <fixstep/stale_temporaries.hpp>

#include "capture_dir.hpp"

namespace fixstep::cli {

namespace {

/// A file's identity: device and inode; for a file not there yet, its absolute path with every
/// existing directory in it resolved (symbolic links, "..", "."), device and inode 0.
struct FileId {
  dev_t dev = 0;
  ino_t ino = 0;
  std::string path;  ///< "" for an existing file
  bool operator==(const FileId&) const = default;
};

std::filesystem::path resolved(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec).lexically_normal();
  std::filesystem::path p = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute : p;
}

std::optional<FileId> id_of(const std::string& path, bool may_be_new) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return FileId{st.st_dev, st.st_ino, ""};
  if (!may_be_new) return std::nullopt;
  return FileId{0, 0, resolved(path).string()};
}

std::string shown(const NamedPath& p) {
  return fmt::format("{} {}", p.role, p.path);
}

[[noreturn]] void refuse_input(const CommandPaths& c, const NamedPath& out, const NamedPath& in) {
  throw PathRefused(fmt::format(
      "fixstep {}: {} is the same file as {}: an output may never overwrite an input (nothing "
      "was written); give another path",
      c.command, shown(out), shown(in)));
}

/// An input that is a capture file already in the capture directory (rewritten or removed).
void refuse_capture_inputs(const CommandPaths& c,
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
void refuse_capture_names(const CommandPaths& c, const NamedPath& out) {
  const std::filesystem::path p = resolved(out.path);
  const std::string name = p.filename().string();
  // compare --csv DIR/compare.csv names the summary's default place: not a clash.
  if (!c.capture_dir || out.role.starts_with("--out") || !is_capture_file(name) ||
      (name == "compare.csv" && out.role == "--csv")) {
    return;
  }
  if (p.parent_path() == resolved(*c.capture_dir)) {
    throw PathRefused(fmt::format(
        "fixstep {}: {} is a file the capture in --out {} writes: one output would overwrite "
        "the other (nothing was written); give each its own path",
        c.command, shown(out), *c.capture_dir));
  }
}

void refuse_same_files(const CommandPaths& c) {
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
      if (seen[i].second != *id) continue;
      if (i < inputs) refuse_input(c, out, seen[i].first);
      throw PathRefused(fmt::format(
          "fixstep {}: {} and {} are the same file: one output would overwrite the other "
          "(nothing was written); give each its own path",
          c.command, shown(seen[i].first), shown(out)));
    }
    refuse_capture_names(c, out);
    seen.emplace_back(out, *id);
  }
}

}  // namespace

void check_paths(const CommandPaths& c) {
  refuse_same_files(c);
  if (c.capture_dir) {
    if (const std::string e = capture_dir_refusal(*c.capture_dir, c.overwrite); !e.empty()) {
      throw PathRefused(fmt::format("fixstep {}: {}", c.command, e));
    }
  }
  for (const NamedPath& out : c.outputs) {
    const std::filesystem::path p(out.path);
    const std::string name = p.filename().string();
    remove_stale_temporaries(p.parent_path(), [&](std::string_view t) { return t == name; });
  }
}

CommandPaths run_paths(const RunOptions& o) {
  CommandPaths c;
  c.command = "run";
  c.inputs = {{"SCENE", o.scene.scene}};
  if (o.input) c.inputs.push_back({"--input", *o.input});
  if (o.csv) c.outputs.push_back({"--csv", *o.csv});
  if (o.record) c.outputs.push_back({"--record", *o.record});
  return c;
}

namespace {
/// --out DIR's manifest and --video FILE with its manifest.
void add_capture_outputs(CommandPaths& c, const std::optional<std::string>& out,
                         const std::optional<std::string>& video) {
  if (out) {
    c.capture_dir = out;
    c.outputs.push_back(
        {"--out DIR's manifest", (std::filesystem::path(*out) / "frames.csv").string()});
  }
  if (video) {
    c.outputs.push_back({"--video", *video});
    c.outputs.push_back({"--video's manifest", video_manifest_path(*video).string()});
  }
}
}  // namespace

CommandPaths render_paths(const RenderOptions& o, const std::string& scene) {
  CommandPaths c;
  c.command = "render";
  c.inputs = {{"SCENE", scene}};
  c.overwrite = o.overwrite;
  if (o.replay) c.inputs.push_back({"--replay", *o.replay});
  add_capture_outputs(c, o.out, o.video);
  return c;
}

CommandPaths compare_paths(const CompareOptions& o) {
  CommandPaths c;
  c.command = "compare";
  c.inputs = {{"SCENE", o.scene}};
  c.overwrite = o.overwrite;
  add_capture_outputs(c, o.out, o.video);
  if (const auto csv = summary_path(o))
    c.outputs.push_back({o.csv   ? "--csv"
                         : o.out ? "--out DIR's summary"
                                 : "--video's summary",
                         csv->string()});
  return c;
}

CommandPaths view_paths(const ViewOptions& o) {
  CommandPaths c;
  c.command = "view";
  c.inputs = {{"SCENE", o.scene.scene}};
  if (o.record) c.outputs.push_back({"--record", *o.record});
  return c;
}

}  // namespace fixstep::cli
