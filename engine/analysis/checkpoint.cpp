#include "engine/analysis/checkpoint.h"

#include <google/protobuf/util/message_differencer.h>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace pfem {

namespace {

constexpr int kFormat = 1;
const std::string kFirstLine = "PFEM checkpoint " + std::to_string(kFormat) + "\n";

std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

template <class T>
void archive_optional(StateArchive& a, std::optional<T>& v) {
  bool present = v.has_value();
  T value = v.value_or(T{});
  a(present), a(value);
  if (a.is_restoring()) v = present ? std::optional<T>(value) : std::nullopt;
}

// Everything but the first line and the checksum.
void archive(StateArchive& a, Checkpoint& c, std::string& engine) {
  a(engine);
  std::string model = a.is_restoring() ? "" : c.run.model.SerializeAsString();
  a(model);
  if (a.is_restoring() && !c.run.model.ParseFromString(model)) throw CheckpointError("its model cannot be read");
  archive_optional(a, c.run.t_end), archive_optional(a, c.run.dt);
  a(c.run.sensitivity), a(c.run.params), a(c.run.drop_geometric_terms), a(c.run.vtk);
  archive_optional(a, c.run.vtk_every);
  a(c.step), a(c.time), a(c.state);
}

// The shortest text that reads back as the value.
template <class T>
std::string shown(const std::optional<T>& v) {
  if (!v) return "not set";
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, *v).ptr);
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s.empty() ? "(all)" : s;
}

}  // namespace

CheckpointedRun checkpointed_run(const pfem::v1::Model& model, const RunOptions& o) {
  return {model, o.t_end, o.dt, o.sensitivity, o.params, o.drop_geometric_terms, !o.vtk_dir.empty(), o.vtk_every};
}

void write_checkpoint(const std::filesystem::path& file, const Checkpoint& checkpoint) {
  StateArchive a = StateArchive::saving();
  Checkpoint c = checkpoint;
  std::string engine = kEngineBuild;
  archive(a, c, engine);
  std::string bytes = kFirstLine + a.bytes();
  std::uint64_t sum = fnv1a(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw std::runtime_error("cannot write the checkpoint " + tmp.string());
  }
  std::filesystem::rename(tmp, file);
}

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  const std::string where = "checkpoint " + file.string() + ": ";
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CheckpointError(where + "cannot be read");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.rfind("PFEM checkpoint ", 0) != 0) throw CheckpointError(where + "is not a pfem checkpoint");
  if (bytes.rfind(kFirstLine, 0) != 0)
    throw CheckpointError(where + "is of another checkpoint format (" + bytes.substr(0, bytes.find('\n')) +
                          "; this engine reads format " + std::to_string(kFormat) + ")");
  Checkpoint c;
  std::string engine;
  try {
    // The build first: another build's file may differ in anything after its name.
    StateArchive head = StateArchive::restoring(bytes.substr(kFirstLine.size(), 128));
    head(engine);
    if (engine != kEngineBuild)
      throw CheckpointError("was written by another engine build (" + engine.substr(0, 12) + ", this one is " +
                            std::string(kEngineBuild).substr(0, 12) +
                            "): a restart continues bit-identically only on the build that wrote it");
    std::uint64_t sum = 0;
    if (bytes.size() < kFirstLine.size() + sizeof sum) throw CheckpointError("is truncated");
    std::memcpy(&sum, bytes.data() + bytes.size() - sizeof sum, sizeof sum);
    bytes.resize(bytes.size() - sizeof sum);
    if (fnv1a(bytes) != sum) throw CheckpointError("is truncated or corrupted (its checksum does not match)");
    StateArchive a = StateArchive::restoring(bytes.substr(kFirstLine.size()));
    archive(a, c, engine);
    if (!a.at_end()) throw CheckpointError("has bytes after its state");
  } catch (const CheckpointError& e) {
    throw CheckpointError(where + e.what());
  }
  return c;
}

void check_same_run(const CheckpointedRun& saved, const CheckpointedRun& now) {
  const std::string prefix = "restart: ";
  google::protobuf::util::MessageDifferencer differ;
  std::string report;
  differ.ReportDifferencesToString(&report);
  if (!differ.Compare(saved.model, now.model)) {
    report = report.substr(0, report.find('\n'));
    throw CheckpointError(prefix + "the model is not the checkpointed run's (" + report + ")");
  }
  const auto differs = [&](const std::string& option, const std::string& was, const std::string& is) {
    if (was != is)
      throw CheckpointError(prefix + option + " is " + is + " here but " + was + " in the checkpointed run");
  };
  differs("t_end", shown(saved.t_end), shown(now.t_end));
  differs("dt", shown(saved.dt), shown(now.dt));
  differs("sensitivity", method_name(saved.sensitivity), method_name(now.sensitivity));
  differs("params", joined(saved.params), joined(now.params));
  differs("drop_geometric_terms", saved.drop_geometric_terms ? "on" : "off", now.drop_geometric_terms ? "on" : "off");
  differs("vtk", saved.vtk ? "on" : "off", now.vtk ? "on" : "off");
  differs("vtk_every", shown(saved.vtk_every), shown(now.vtk_every));
}

}  // namespace pfem
