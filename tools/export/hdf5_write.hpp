#pragma once
/// @file
/// The few HDF5 writes `lagrange export` makes (H5Cpp): text attributes,
/// a dataset with its units, and a block of rows into a dataset made whole
/// up front. Shared by the channels' groups (export.cpp) and /tracking
/// (tracking_export.cpp).

#include <H5Cpp.h>

#include <string>
#include <vector>

namespace lagrange::tools::hdf5 {

inline H5::StrType textType() { return H5::StrType(H5::PredType::C_S1, H5T_VARIABLE); }

inline void textAttribute(H5::H5Object& at, const std::string& name, const std::string& value) {
  const H5::StrType type = textType();
  H5::Attribute a = at.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  a.write(type, value);
}

inline void textListAttribute(H5::H5Object& at, const std::string& name,
                              const std::vector<std::string>& values) {
  const H5::StrType type = textType();
  const hsize_t n = values.size();
  H5::Attribute a = at.createAttribute(name, type, H5::DataSpace(1, &n));
  std::vector<const char*> pointers;
  for (const std::string& v : values) pointers.push_back(v.c_str());
  a.write(type, pointers.data());
}

/// A scalar number attribute (an int64 or a double, as `type` says).
inline void numberAttribute(H5::H5Object& at, const std::string& name, const H5::PredType& type,
                            const void* value) {
  H5::Attribute a = at.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  a.write(type, value);
}

inline H5::DataSet dataset(H5::Group& g, const std::string& name, const H5::PredType& type,
                           std::vector<hsize_t> dims, const std::string& unit,
                           const std::string& description) {
  H5::DataSet d = g.createDataSet(name, type, H5::DataSpace(static_cast<int>(dims.size()), dims.data()));
  if (!unit.empty()) textAttribute(d, "units", unit);
  if (!description.empty()) textAttribute(d, "description", description);
  return d;
}

/// Writes rows [first, first + count) of a dataset (its other dimensions whole).
inline void writeRows(H5::DataSet& d, const H5::PredType& type, const void* data, size_t first,
                      size_t count) {
  H5::DataSpace file_space = d.getSpace();
  const int rank = file_space.getSimpleExtentNdims();
  std::vector<hsize_t> dims(static_cast<size_t>(rank)), start(static_cast<size_t>(rank), 0);
  file_space.getSimpleExtentDims(dims.data());
  start[0] = first;
  dims[0] = count;
  file_space.selectHyperslab(H5S_SELECT_SET, dims.data(), start.data());
  const H5::DataSpace memory(rank, dims.data());
  d.write(data, type, memory, file_space);
}

}  // namespace lagrange::tools::hdf5
