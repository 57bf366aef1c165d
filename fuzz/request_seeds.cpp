// Writes the request fuzzer's seed corpus: for each model file given, a SubmitJob, an Evaluate
// (a functional of its first recorder, a value for its first parameter) and a ValidateModel
// request, each encoded as request_fuzzer.cpp reads it.
//   request_seeds OUT_DIR MODEL.json...
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/model_io.h"
#include "fuzz/request_kind.h"
#include "pfem/v1/service.pb.h"

namespace {

void write_seed(const std::filesystem::path& file, pfem::fuzz::RequestKind kind,
                const google::protobuf::Message& request) {
  std::ofstream out(file, std::ios::binary);
  out.put(static_cast<char>(kind));
  request.SerializeToOstream(&out);
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

template <typename Request>
void add_parameter_value(const pfem::v1::Model& model, Request* request) {
  if (model.parameters().empty()) return;
  auto* value = request->add_parameter_values();
  value->set_name(model.parameters(0).name());
  value->set_value(1.5);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: request_seeds OUT_DIR MODEL.json...\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  for (int i = 2; i < argc; ++i) {
    const pfem::v1::Model model = pfem::read_model_file(argv[i]);
    const std::string stem = std::filesystem::path(argv[i]).stem().string();

    pfem::v1::SubmitJobRequest submit;
    *submit.mutable_model() = model;
    add_parameter_value(model, &submit);
    submit.mutable_options()->set_t_end(0.01);
    submit.set_timeout_seconds(60.0);
    write_seed(out / (stem + ".submit"), pfem::fuzz::RequestKind::kSubmitJob, submit);

    pfem::v1::EvaluateRequest evaluate;
    *evaluate.mutable_model() = model;
    add_parameter_value(model, &evaluate);
    if (!model.recorders().empty()) {
      auto* functional = evaluate.add_functionals();
      functional->set_recorder(model.recorders(0).name());
      functional->set_kind(pfem::v1::Functional::KIND_MAX);
    }
    if (!model.parameters().empty()) evaluate.add_params(model.parameters(0).name());
    evaluate.set_t_end(0.01);
    write_seed(out / (stem + ".evaluate"), pfem::fuzz::RequestKind::kEvaluate, evaluate);

    pfem::v1::ValidateModelRequest validate;
    *validate.mutable_model() = model;
    write_seed(out / (stem + ".validate"), pfem::fuzz::RequestKind::kValidateModel, validate);
  }
  return 0;
}
