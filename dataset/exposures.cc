#include "dataset/exposures.h"

#include <fstream>
#include <iomanip>
#include <sstream>

#include "common/error.h"
#include "common/text_records.h"
#include "common/tum_io.h"
#include "dataset/dataset_files.h"
#include "dataset/format_version.h"
#include "dataset/text_fields.h"

namespace depot::dataset {
namespace {

ExposureRecord parse_record(const std::vector<std::string>& f, const std::string& where) {
  if (f.size() != 4)
    fail(where,
         "expected 4 fields (timestamp exposure gain light), found " + std::to_string(f.size()));
  ExposureRecord r;
  r.timestamp = parse_number_field(f[0], "timestamp", where);
  r.exposure = parse_number_field(f[1], "exposure", where);
  r.gain = parse_number_field(f[2], "gain", where);
  r.light = parse_number_field(f[3], "light", where);
  if (r.exposure < 0) fail(where, "exposure " + f[1] + " is negative");
  if (r.gain < 1) fail(where, "gain " + f[2] + " is below 1");
  if (r.light < 0) fail(where, "light " + f[3] + " is negative");
  return r;
}

}  // namespace

void write_exposures(const std::string& dataset_dir, const std::string& scenario_name,
                     const std::vector<ExposureRecord>& records) {
  std::string text = "# how each colour frame was exposed; light = the scene's light level\n" +
                     file_header_line(scenario_name) + "# timestamp exposure gain light\n";
  for (const ExposureRecord& r : records) {
    std::ostringstream line;
    line << std::setprecision(7) << format_timestamp(r.timestamp) << ' ' << r.exposure << ' '
         << r.gain << ' ' << r.light << '\n';
    text += line.str();
  }
  write_text_file_atomic(dataset_file(dataset_dir, kExposuresFile), text);
}

std::vector<ExposureRecord> read_exposures(const std::string& dataset_dir) {
  check_format_version(dataset_dir);
  const std::string path = dataset_file(dataset_dir, kExposuresFile);
  std::ifstream in(path);
  if (!in)
    fail(path, "cannot open file (exposures are written where the camera forms its colour image)");
  std::vector<ExposureRecord> records;
  for_each_record(in, path, [&](const std::string& where, const std::vector<std::string>& f) {
    records.push_back(parse_record(f, where));
  });
  if (in.bad()) fail(path, "read error");
  return records;
}

}  // namespace depot::dataset
