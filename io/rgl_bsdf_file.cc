#include "io/rgl_bsdf_file.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/spectral_rgb.h"
#include "io/input_file.h"

namespace brdfit {

namespace {

constexpr double kHalfPi = kPi / 2;

class Fields {
 public:
  Fields(const TensorFile& f, const std::filesystem::path& path) : f_(f), path_(path) {}

  const TensorField& Get(const std::string& name, TensorType dtype, std::size_t rank) const {
    const TensorField* t = f_.Find(name);
    if (!t) throw InputError(path_, "not an RGL .bsdf file: field '" + name + "' is missing");
    if (t->dtype != dtype) {
      throw InputError(path_, "field '" + name + "' is " + TensorTypeName(t->dtype) +
                                  ", expected " + TensorTypeName(dtype));
    }
    if (t->shape.size() != rank) {
      throw InputError(path_, "field '" + name + "' has shape " + t->ShapeString() +
                                  ", expected rank " + std::to_string(rank));
    }
    return *t;
  }

  std::vector<double> Values(const TensorField& t) const { return t.AsDoubles(path_); }

  void Extent(const TensorField& t, std::size_t axis, std::uint64_t expected,
              const std::string& what) const {
    if (t.shape[axis] != expected) {
      throw InputError(path_, "field '" + t.name + "' has shape " + t.ShapeString() + ": axis " +
                                  std::to_string(axis) + " must be " + what + " (" +
                                  std::to_string(expected) + ")");
    }
  }

  // Every value finite and at least `min` (strictly above it when `strict`).
  void Check(const TensorField& t, const std::vector<double>& v, double min, bool strict) const {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i]) || v[i] < min || (strict && v[i] == min)) {
        throw InputError(path_, "field '" + t.name + "' holds " + std::to_string(v[i]) +
                                    " at element " + std::to_string(i) + " (must be finite and " +
                                    (strict ? "> " : ">= ") + std::to_string(min) + ")");
      }
    }
  }

 private:
  const TensorFile& f_;
  const std::filesystem::path& path_;
};

int Extent32(const TensorField& t, std::size_t axis, const std::filesystem::path& path, int min) {
  const std::uint64_t e = t.shape[axis];
  if (e < static_cast<std::uint64_t>(min) || e > 4096) {
    throw InputError(path, "field '" + t.name + "' has shape " + t.ShapeString() + ": axis " +
                               std::to_string(axis) + " must be " + std::to_string(min) + "..4096");
  }
  return static_cast<int>(e);
}

}  // namespace

RglBsdf RglBsdfFromTensors(const TensorFile& file, const std::filesystem::path& path) {
  const Fields f(file, path);
  RglBsdf b;
  const TensorField& description = f.Get("description", TensorType::kUInt8, 1);
  b.description.assign(description.bytes.begin(), description.bytes.end());
  const TensorField& jacobian = f.Get("jacobian", TensorType::kUInt8, 1);
  f.Extent(jacobian, 0, 1, "1");
  b.jacobian = jacobian.bytes[0] != 0;

  const TensorField& theta_i = f.Get("theta_i", TensorType::kFloat32, 1);
  const TensorField& phi_i = f.Get("phi_i", TensorType::kFloat32, 1);
  b.theta_i = f.Values(theta_i);
  b.phi_i = f.Values(phi_i);
  if (b.theta_i.empty() || b.theta_i.size() > 4096) {
    throw InputError(path, "field 'theta_i' has " + std::to_string(b.theta_i.size()) +
                               " values (1..4096 are read)");
  }
  for (std::size_t i = 0; i < b.theta_i.size(); ++i) {
    if (!(b.theta_i[i] >= 0 && b.theta_i[i] <= kHalfPi + 1e-5) ||
        (i > 0 && !(b.theta_i[i] > b.theta_i[i - 1]))) {
      throw InputError(path, "field 'theta_i' must increase strictly within [0, pi/2]; element " +
                                 std::to_string(i) + " is " + std::to_string(b.theta_i[i]));
    }
  }
  if (b.phi_i.empty()) throw InputError(path, "field 'phi_i' is empty");
  if (b.phi_i.size() > 2) {
    throw InputError(path, "anisotropic .bsdf (phi_i has " + std::to_string(b.phi_i.size()) +
                               " values): brdfit reads isotropic files only");
  }
  for (double v : b.phi_i) {
    if (!std::isfinite(v)) throw InputError(path, "field 'phi_i' is not finite");
  }
  if (b.phi_i.size() == 2 && !(b.phi_i[1] > b.phi_i[0])) {
    throw InputError(path, "field 'phi_i' must increase strictly");
  }
  const auto np = static_cast<std::uint64_t>(b.phi_i.size());
  const auto nt = static_cast<std::uint64_t>(b.theta_i.size());

  const TensorField& ndf = f.Get("ndf", TensorType::kFloat32, 2);
  b.ndf_rows = Extent32(ndf, 0, path, 2);
  b.ndf_cols = Extent32(ndf, 1, path, 2);
  b.ndf = f.Values(ndf);
  f.Check(ndf, b.ndf, 0, false);
  const TensorField& sigma = f.Get("sigma", TensorType::kFloat32, 2);
  b.sigma_rows = Extent32(sigma, 0, path, 2);
  b.sigma_cols = Extent32(sigma, 1, path, 2);
  b.sigma = f.Values(sigma);
  f.Check(sigma, b.sigma, 0, true);

  const TensorField& vndf = f.Get("vndf", TensorType::kFloat32, 4);
  f.Extent(vndf, 0, np, "phi_i's size");
  f.Extent(vndf, 1, nt, "theta_i's size");
  b.rows = Extent32(vndf, 2, path, 2);
  b.cols = Extent32(vndf, 3, path, 2);
  b.vndf = f.Values(vndf);
  f.Check(vndf, b.vndf, 0, false);

  const TensorField& luminance = f.Get("luminance", TensorType::kFloat32, 4);
  for (std::size_t a = 0; a < 4; ++a) f.Extent(luminance, a, vndf.shape[a], "vndf's");
  b.luminance = f.Values(luminance);
  f.Check(luminance, b.luminance, 0, false);

  const TensorField* rgb = file.Find("rgb");
  const TensorField* spectra = file.Find("spectra");
  if (rgb && spectra) throw InputError(path, "both 'rgb' and 'spectra' fields: which one?");
  if (!rgb && !spectra) {
    throw InputError(path, "not an RGL .bsdf file: neither an 'rgb' nor a 'spectra' field");
  }
  const TensorField& values = f.Get(rgb ? "rgb" : "spectra", TensorType::kFloat32, 5);
  f.Extent(values, 0, np, "phi_i's size");
  f.Extent(values, 1, nt, "theta_i's size");
  f.Extent(values, 3, vndf.shape[2], "vndf's");
  f.Extent(values, 4, vndf.shape[3], "vndf's");
  if (rgb) {
    f.Extent(values, 2, 3, "3 (R, G, B)");
  } else {
    const TensorField& wavelengths = f.Get("wavelengths", TensorType::kFloat32, 1);
    b.wavelengths = f.Values(wavelengths);
    f.Extent(values, 2, b.wavelengths.size(), "the number of wavelengths");
    if (b.wavelengths.size() < 2 || b.wavelengths.size() > 4096) {
      throw InputError(path, "field 'wavelengths' needs 2..4096 values");
    }
    for (std::size_t i = 0; i < b.wavelengths.size(); ++i) {
      if (!(b.wavelengths[i] > 0 && std::isfinite(b.wavelengths[i])) ||
          (i > 0 && !(b.wavelengths[i] > b.wavelengths[i - 1]))) {
        throw InputError(path, "field 'wavelengths' must be positive and increase strictly");
      }
    }
    try {
      SrgbWeights(b.wavelengths);
    } catch (const std::invalid_argument&) {
      throw InputError(path, "field 'wavelengths' (" + std::to_string(b.wavelengths.front()) +
                                 ".." + std::to_string(b.wavelengths.back()) +
                                 " nm) does not cover enough of the visible range for R, G and B");
    }
  }
  b.channels = static_cast<int>(values.shape[2]);
  b.values = f.Values(values);
  f.Check(values, b.values, -HUGE_VAL, false);

  if (const TensorField* valid = file.Find("valid")) {
    // Optional per-sample mask on the warped grid. The format's readers ignore it; one of
    // another layout is reported and left out rather than refusing the measurement.
    if (valid->dtype == TensorType::kUInt8 && valid->shape == vndf.shape) {
      b.valid = valid->bytes;
    } else {
      b.notes.push_back("field 'valid' (" + std::string(TensorTypeName(valid->dtype)) + " " +
                        valid->ShapeString() + ") is not a uint8 mask of vndf's shape " +
                        vndf.ShapeString() + ": not used");
    }
  }

  // Densities that integrate to zero cannot be inverted.
  const std::size_t cells = static_cast<std::size_t>(b.rows) * b.cols;
  for (std::size_t s = 0; s < np * nt; ++s) {
    double sum = 0;
    for (std::size_t i = 0; i < cells; ++i) sum += b.vndf[s * cells + i];
    if (!(sum > 0)) {
      throw InputError(path, "field 'vndf' is zero everywhere in slice " + std::to_string(s) +
                                 " (phi_i " + std::to_string(s / nt) + ", theta_i " +
                                 std::to_string(s % nt) + ")");
    }
  }
  return b;
}

RglBsdf ReadRglBsdf(const std::filesystem::path& path) {
  return RglBsdfFromTensors(ReadTensorFile(path), path);
}

void WriteRglBsdf(const RglBsdf& b, const std::filesystem::path& path) {
  const auto np = static_cast<std::uint64_t>(b.phi_i.size()),
             nt = static_cast<std::uint64_t>(b.theta_i.size());
  const auto rows = static_cast<std::uint64_t>(b.rows), cols = static_cast<std::uint64_t>(b.cols);
  TensorFile f;
  f.fields.push_back(UInt8Field("description", {b.description.size()},
                                {b.description.begin(), b.description.end()}));
  f.fields.push_back(UInt8Field("jacobian", {1}, {static_cast<std::uint8_t>(b.jacobian)}));
  f.fields.push_back(Float32Field("theta_i", {nt}, b.theta_i));
  f.fields.push_back(Float32Field("phi_i", {np}, b.phi_i));
  f.fields.push_back(Float32Field(
      "ndf", {static_cast<std::uint64_t>(b.ndf_rows), static_cast<std::uint64_t>(b.ndf_cols)},
      b.ndf));
  f.fields.push_back(Float32Field(
      "sigma", {static_cast<std::uint64_t>(b.sigma_rows), static_cast<std::uint64_t>(b.sigma_cols)},
      b.sigma));
  f.fields.push_back(Float32Field("vndf", {np, nt, rows, cols}, b.vndf));
  f.fields.push_back(
      Float32Field("luminance", {np, nt, rows, cols}, b.luminance.empty() ? b.vndf : b.luminance));
  const auto channels = static_cast<std::uint64_t>(b.channels);
  if (b.wavelengths.empty()) {
    f.fields.push_back(Float32Field("rgb", {np, nt, channels, rows, cols}, b.values));
  } else {
    f.fields.push_back(Float32Field("wavelengths", {channels}, b.wavelengths));
    f.fields.push_back(Float32Field("spectra", {np, nt, channels, rows, cols}, b.values));
  }
  if (!b.valid.empty()) f.fields.push_back(UInt8Field("valid", {np, nt, rows, cols}, b.valid));
  WriteTensorFile(f, path);
}

Table ReadRglBsdfTable(const std::filesystem::path& path, const Grid& grid, RglTabulation* counts) {
  const RglBsdf b = ReadRglBsdf(path);
  RglTabulation n;
  Table t = TabulateRglBsdf(b, grid, &n);
  if (t.CountValid() == 0) {
    throw InputError(path, "no cell of the grid is covered by the file (theta_i up to " +
                               std::to_string(b.theta_i.back() * 180 / kPi) + " deg)");
  }
  t.provenance.source = path.string();
  t.provenance.generator = "rgl-bsdf";
  nlohmann::json j;
  j["description"] = b.description;
  j["spectral"] = !b.wavelengths.empty();
  t.provenance.parameters_json = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (counts) *counts = n;
  return t;
}

}  // namespace brdfit
