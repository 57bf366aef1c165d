#include "engine/io/model_io.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "engine/io/model_checks.h"

namespace pfem {

namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;

const FieldDescriptor* find_field(const Descriptor& d, const std::string& key) {
  for (int i = 0; i < d.field_count(); ++i)
    if (d.field(i)->name() == key || d.field(i)->json_name() == key) return d.field(i);
  return nullptr;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (std::tolower(a[i - 1]) != std::tolower(b[j - 1]))});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// Every path below Model where a field called key exists ("structure.self_weight",
// "structure.materials[].bilinear.fy").
void paths_of(const Descriptor& d, const std::string& prefix, const std::string& key, int depth,
              std::vector<std::string>& out) {
  for (int i = 0; i < d.field_count(); ++i) {
    const FieldDescriptor* f = d.field(i);
    const std::string path = prefix + f->name() + (f->is_repeated() ? "[]" : "");
    if (f->name() == key || f->json_name() == key) out.push_back(prefix + f->name());
    if (f->message_type() && depth < 6) paths_of(*f->message_type(), path + ".", key, depth + 1, out);
  }
}

// The unknown field `key` of message d: where a field of that name is (the same name in another
// message), or else the closest name of d (at most a third of its letters off, at least one).
std::string unknown_field_message(const Descriptor& d, const std::string& key) {
  const std::string message = "unknown field of " + d.name();
  std::vector<std::string> places;
  paths_of(*pfem::v1::Model::descriptor(), "", key, 0, places);
  if (!places.empty()) {
    std::string where;
    for (std::size_t i = 0; i < places.size() && i < 3; ++i) where += (i ? " or " : "") + places[i];
    return message + "; it belongs in " + where;
  }
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(1, key.size() / 3) + 1;
  for (int i = 0; i < d.field_count(); ++i)
    if (const std::size_t e = edit_distance(key, d.field(i)->name()); e < best_distance)
      best = d.field(i)->name(), best_distance = e;
  return best.empty() ? message : message + "; did you mean '" + best + "'?";
}

// The unknown fields of the JSON value v as message d, with their paths.
void unknown_fields(const nlohmann::ordered_json& v, const Descriptor& d, const std::string& path,
                    std::vector<FieldError>& out) {
  if (!v.is_object()) return;
  for (const auto& [key, value] : v.items()) {
    const std::string here = path.empty() ? key : path + "." + key;
    const FieldDescriptor* f = find_field(d, key);
    if (!f) {
      out.push_back({here, unknown_field_message(d, key)});
      continue;
    }
    if (!f->message_type()) continue;
    if (f->is_repeated() && value.is_array()) {
      for (std::size_t i = 0; i < value.size(); ++i)
        unknown_fields(value[i], *f->message_type(), here + "[" + std::to_string(i) + "]", out);
    } else {
      unknown_fields(value, *f->message_type(), here, out);
    }
  }
}

// Why protobuf refused json, as field errors: the line and column of a syntax error, every
// unknown field with a suggestion; otherwise protobuf's own message.
std::vector<FieldError> diagnose(std::string_view json, std::string protobuf_message) {
  try {
    const auto value = nlohmann::ordered_json::parse(json.begin(), json.end());  // keys in file order
    std::vector<FieldError> errors;
    unknown_fields(value, *pfem::v1::Model::descriptor(), "", errors);
    if (!errors.empty()) return errors;
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();  // "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
    const std::string marker = "parse error at ";
    if (const auto at = what.find(marker); at != std::string::npos) what = what.substr(at + marker.size());
    return {{"model", "invalid JSON at " + what}};
  } catch (const nlohmann::json::exception& e) {  // a number out of range: 2.1e555 (the fuzzer's)
    std::string what = e.what();  // "[json.exception.out_of_range.406] number overflow parsing '...'"
    if (const auto at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
    return {{"model", "invalid JSON: " + what}};
  }
  std::replace(protobuf_message.begin(), protobuf_message.end(), '\n', ' ');  // spans lines (text, caret)
  return {{"model", "invalid JSON: " + protobuf_message}};
}

}  // namespace

pfem::v1::Model parse_model_json(std::string_view json) {
  pfem::v1::Model model;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(json.data(), json.size()), &model, options);
  if (!status.ok()) throw ModelError(diagnose(json, std::string(status.message())));
  return model;
}

pfem::v1::Model read_model_file(const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path)) throw ModelError(path.string(), "is a directory, not a model file");
  std::ifstream in(path);
  if (!in) throw ModelError(path.string(), "cannot open the model file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_model_json(buffer.str());
}

std::vector<FieldError> validate_model(const pfem::v1::Model& model) {
  ModelChecker checker(model);
  return checker.run();
}

}  // namespace pfem
