// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingLogHDF5.h
 * @brief Private HDF5 helpers shared by the training-log writer and reader (not installed).
 *
 * RAII handles, error capture (HDF5's own stack printing is silenced; failures become
 * std::runtime_error naming the file and the object) and small typed read/write helpers.
 */
#ifndef vis4gs_TrainingLogHDF5_h
#define vis4gs_TrainingLogHDF5_h

#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vis4gs
{
namespace h5
{

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle
{
public:
  Handle() = default;
  explicit Handle(hid_t id)
    : Id(id)
  {
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept
    : Id(std::exchange(other.Id, H5I_INVALID_HID))
  {
  }
  Handle& operator=(Handle&& other) noexcept
  {
    if (this != &other)
    {
      this->Reset();
      this->Id = std::exchange(other.Id, H5I_INVALID_HID);
    }
    return *this;
  }
  ~Handle() { this->Reset(); }
  hid_t Get() const { return this->Id; }
  operator hid_t() const { return this->Id; }
  bool Valid() const { return this->Id >= 0; }
  void Reset();

private:
  hid_t Id = H5I_INVALID_HID;
};

/// Silences HDF5's automatic error printing for the lifetime of the object (per thread).
class ErrorSilencer
{
public:
  ErrorSilencer();
  ~ErrorSilencer();
  ErrorSilencer(const ErrorSilencer&) = delete;
  ErrorSilencer& operator=(const ErrorSilencer&) = delete;

private:
  H5E_auto2_t Func = nullptr;
  void* Data = nullptr;
};

/// The innermost message on HDF5's error stack ("" when empty).
std::string LastErrorMessage();

/// Throws std::runtime_error("<file>: <what>[: <hdf5 detail>]").
[[noreturn]] void Fail(const std::string& file, const std::string& what);

/// Throws when @p id is negative.
hid_t Check(hid_t id, const std::string& file, const std::string& what);
void CheckStatus(herr_t status, const std::string& file, const std::string& what);

bool LinkExists(hid_t loc, const std::string& path);
bool IsGroup(hid_t loc, const std::string& path);
bool IsDataset(hid_t loc, const std::string& path);

/// Dimensions of a dataset.
std::vector<hsize_t> Dims(hid_t dset);

/// Writes a scalar attribute.
void WriteStringAttribute(hid_t obj, const std::string& name, const std::string& value);
void WriteIntAttribute(hid_t obj, const std::string& name, std::int64_t value);
/// Reads a scalar attribute; returns false when it does not exist; throws on bad type.
bool ReadStringAttribute(hid_t obj,
  const std::string& name,
  std::string& value,
  const std::string& file);
bool ReadIntAttribute(hid_t obj,
  const std::string& name,
  std::int64_t& value,
  const std::string& file);

/// Reads the whole of a string dataset (fixed or variable length) as UTF-8 strings.
std::vector<std::string> ReadStrings(hid_t dset, const std::string& file, const std::string& what);
/// Writes a 1-D variable-length UTF-8 string dataset.
void WriteStrings(hid_t loc,
  const std::string& name,
  const std::vector<std::string>& values,
  int deflateLevel);

/// Creation property list for a chunked, shuffled, deflated dataset.
Handle ChunkedPlist(const std::vector<hsize_t>& chunk, int deflateLevel);

/**
 * Creates a dataset of @p dims (first dimension unlimited), chunked by @p chunk and
 * compressed, and writes @p data (memory type @p memType) into it unless dims[0] is 0.
 */
Handle CreateAndWrite(hid_t loc,
  const std::string& name,
  hid_t fileType,
  hid_t memType,
  const std::vector<hsize_t>& dims,
  const std::vector<hsize_t>& chunk,
  int deflateLevel,
  const void* data,
  const std::string& file);

/// Appends @p n rows of a 1-D extendable dataset.
void Append1D(hid_t dset,
  hid_t memType,
  std::size_t n,
  const void* data,
  const std::string& file,
  const std::string& what);

/// Appends @p n rows (each of the dataset's other dimensions) to an extendable dataset.
void AppendRows(hid_t dset,
  hid_t memType,
  std::size_t n,
  const void* data,
  const std::string& file,
  const std::string& what);

/// Reads a whole dataset converted to @p memType into @p out (which must be large enough).
void ReadAll(hid_t dset,
  hid_t memType,
  void* out,
  const std::string& file,
  const std::string& what);

/// Memory type for T.
template <typename T>
hid_t MemType();
template <>
inline hid_t MemType<float>()
{
  return H5T_NATIVE_FLOAT;
}
template <>
inline hid_t MemType<double>()
{
  return H5T_NATIVE_DOUBLE;
}
template <>
inline hid_t MemType<std::int32_t>()
{
  return H5T_NATIVE_INT32;
}
template <>
inline hid_t MemType<std::int64_t>()
{
  return H5T_NATIVE_INT64;
}
template <>
inline hid_t MemType<std::uint8_t>()
{
  return H5T_NATIVE_UINT8;
}

} // namespace h5
} // namespace vis4gs

#endif
