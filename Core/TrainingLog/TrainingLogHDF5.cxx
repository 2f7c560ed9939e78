// SPDX-License-Identifier: BSD-3-Clause
#include "TrainingLogHDF5.h"

#include <algorithm>
#include <cstring>

namespace
{
// HDF5 closes every file still open in an exit handler. A file whose writes failed (a full
// disk) cannot be closed, and HDF5 1.10's handler then crashes (SIGSEGV in H5F__close_cb) after
// the program has reported the error; it must run before any other HDF5 call to take effect.
// Every writer here closes its files itself, and a log is valid up to its last flush anyway.
const bool NoHdf5ExitHandler = H5dont_atexit() >= 0;
}

namespace vis4gs
{
namespace h5
{

//------------------------------------------------------------------------------
void Handle::Reset()
{
  if (this->Id < 0)
  {
    return;
  }
  ErrorSilencer silence;
  switch (H5Iget_type(this->Id))
  {
    case H5I_FILE:
      H5Fclose(this->Id);
      break;
    case H5I_GROUP:
      H5Gclose(this->Id);
      break;
    case H5I_DATASET:
      H5Dclose(this->Id);
      break;
    case H5I_DATASPACE:
      H5Sclose(this->Id);
      break;
    case H5I_DATATYPE:
      H5Tclose(this->Id);
      break;
    case H5I_ATTR:
      H5Aclose(this->Id);
      break;
    case H5I_GENPROP_LST:
      H5Pclose(this->Id);
      break;
    default:
      break;
  }
  this->Id = H5I_INVALID_HID;
}

//------------------------------------------------------------------------------
ErrorSilencer::ErrorSilencer()
{
  H5Eget_auto2(H5E_DEFAULT, &this->Func, &this->Data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

//------------------------------------------------------------------------------
ErrorSilencer::~ErrorSilencer()
{
  H5Eset_auto2(H5E_DEFAULT, this->Func, this->Data);
}

namespace
{
herr_t InnermostMessage(unsigned n, const H5E_error2_t* err, void* clientData)
{
  if (n == 0 && err && err->desc)
  {
    *static_cast<std::string*>(clientData) = err->desc;
  }
  return 0;
}
} // namespace

//------------------------------------------------------------------------------
std::string LastErrorMessage()
{
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, &InnermostMessage, &message);
  // A failed system call: HDF5's file driver message holds the time, the buffer address and the
  // byte counts around the one part a person needs, the system's "error message = '...'".
  const std::string key = "error message = '";
  const std::size_t start = message.find(key);
  const std::size_t end =
    start == std::string::npos ? start : message.find('\'', start + key.size());
  if (end != std::string::npos)
  {
    return message.substr(start + key.size(), end - start - key.size());
  }
  return message;
}

//------------------------------------------------------------------------------
void Fail(const std::string& file, const std::string& what)
{
  std::string detail = LastErrorMessage();
  H5Eclear2(H5E_DEFAULT);
  throw std::runtime_error(file + ": " + what + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

//------------------------------------------------------------------------------
hid_t Check(hid_t id, const std::string& file, const std::string& what)
{
  if (id < 0)
  {
    Fail(file, what);
  }
  return id;
}

//------------------------------------------------------------------------------
void CheckStatus(herr_t status, const std::string& file, const std::string& what)
{
  if (status < 0)
  {
    Fail(file, what);
  }
}

//------------------------------------------------------------------------------
bool LinkExists(hid_t loc, const std::string& path)
{
  ErrorSilencer silence;
  // Check every component so that "a/b" does not fail when "a" is missing.
  std::size_t pos = 0;
  while (true)
  {
    std::size_t next = path.find('/', pos + 1);
    std::string prefix = path.substr(0, next);
    if (!prefix.empty() && prefix != "/" && H5Lexists(loc, prefix.c_str(), H5P_DEFAULT) <= 0)
    {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    if (next == std::string::npos)
    {
      return true;
    }
    pos = next;
  }
}

namespace
{
H5O_type_t ObjectType(hid_t loc, const std::string& path)
{
  if (!LinkExists(loc, path))
  {
    return H5O_TYPE_UNKNOWN;
  }
  ErrorSilencer silence;
  H5O_info_t info;
  // Only the type: the full info (H5O_INFO_ALL, the 1.8 default) walks a dataset's whole
  // chunk index to size it, which dominated opening the datasets of a history query.
#if H5_VERSION_GE(1, 10, 3) && !H5_VERSION_GE(1, 12, 0)
  if (H5Oget_info_by_name2(loc, path.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0)
#else
  if (H5Oget_info_by_name(loc, path.c_str(), &info, H5P_DEFAULT) < 0)
#endif
  {
    H5Eclear2(H5E_DEFAULT);
    return H5O_TYPE_UNKNOWN;
  }
  return info.type;
}
} // namespace

//------------------------------------------------------------------------------
bool IsGroup(hid_t loc, const std::string& path)
{
  return ObjectType(loc, path) == H5O_TYPE_GROUP;
}

//------------------------------------------------------------------------------
bool IsDataset(hid_t loc, const std::string& path)
{
  return ObjectType(loc, path) == H5O_TYPE_DATASET;
}

//------------------------------------------------------------------------------
std::vector<hsize_t> Dims(hid_t dset)
{
  Handle space(H5Dget_space(dset));
  if (!space.Valid())
  {
    return {};
  }
  int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0)
  {
    return {};
  }
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

namespace
{
Handle Utf8VariableString()
{
  Handle type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  return type;
}
} // namespace

//------------------------------------------------------------------------------
void WriteStringAttribute(hid_t obj, const std::string& name, const std::string& value)
{
  Handle type = Utf8VariableString();
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(obj, name.c_str()) > 0)
  {
    H5Adelete(obj, name.c_str());
  }
  Handle attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT));
  const char* ptr = value.c_str();
  if (!attr.Valid() || H5Awrite(attr, type, &ptr) < 0)
  {
    throw std::runtime_error("cannot write attribute " + name);
  }
}

//------------------------------------------------------------------------------
void WriteIntAttribute(hid_t obj, const std::string& name, std::int64_t value)
{
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(obj, name.c_str()) > 0)
  {
    H5Adelete(obj, name.c_str());
  }
  Handle attr(H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT));
  if (!attr.Valid() || H5Awrite(attr, H5T_NATIVE_INT64, &value) < 0)
  {
    throw std::runtime_error("cannot write attribute " + name);
  }
}

//------------------------------------------------------------------------------
bool ReadStringAttribute(hid_t obj,
  const std::string& name,
  std::string& value,
  const std::string& file)
{
  ErrorSilencer silence;
  if (H5Aexists(obj, name.c_str()) <= 0)
  {
    H5Eclear2(H5E_DEFAULT);
    return false;
  }
  Handle attr(
    Check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), file, "cannot open attribute " + name));
  Handle type(H5Aget_type(attr));
  Handle space(H5Aget_space(attr));
  if (H5Tget_class(type) != H5T_STRING || H5Sget_simple_extent_npoints(space) != 1)
  {
    throw std::runtime_error(file + ": attribute " + name + " is not a single string");
  }
  if (H5Tis_variable_str(type) > 0)
  {
    Handle mem = Utf8VariableString();
    char* ptr = nullptr;
    CheckStatus(H5Aread(attr, mem, &ptr), file, "cannot read attribute " + name);
    value = ptr ? ptr : "";
    H5free_memory(ptr);
  }
  else
  {
    std::size_t size = H5Tget_size(type);
    std::vector<char> buffer(size + 1, '\0');
    Handle mem(H5Tcopy(H5T_C_S1));
    H5Tset_size(mem, size + 1);
    H5Tset_strpad(mem, H5T_STR_NULLTERM);
    CheckStatus(H5Aread(attr, mem, buffer.data()), file, "cannot read attribute " + name);
    value.assign(buffer.data(), strnlen(buffer.data(), size));
  }
  return true;
}

//------------------------------------------------------------------------------
bool ReadIntAttribute(hid_t obj,
  const std::string& name,
  std::int64_t& value,
  const std::string& file)
{
  ErrorSilencer silence;
  if (H5Aexists(obj, name.c_str()) <= 0)
  {
    H5Eclear2(H5E_DEFAULT);
    return false;
  }
  Handle attr(
    Check(H5Aopen(obj, name.c_str(), H5P_DEFAULT), file, "cannot open attribute " + name));
  Handle type(H5Aget_type(attr));
  Handle space(H5Aget_space(attr));
  H5T_class_t cls = H5Tget_class(type);
  if ((cls != H5T_INTEGER && cls != H5T_FLOAT) || H5Sget_simple_extent_npoints(space) != 1)
  {
    throw std::runtime_error(file + ": attribute " + name + " is not a single number");
  }
  if (cls == H5T_FLOAT)
  {
    double d = 0;
    CheckStatus(H5Aread(attr, H5T_NATIVE_DOUBLE, &d), file, "cannot read attribute " + name);
    value = static_cast<std::int64_t>(d);
  }
  else
  {
    CheckStatus(H5Aread(attr, H5T_NATIVE_INT64, &value), file, "cannot read attribute " + name);
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<std::string> ReadStrings(hid_t dset, const std::string& file, const std::string& what)
{
  Handle type(Check(H5Dget_type(dset), file, "cannot read the type of " + what));
  if (H5Tget_class(type) != H5T_STRING)
  {
    throw std::runtime_error(file + ": " + what + " is not a string dataset");
  }
  Handle space(H5Dget_space(dset));
  hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 0)
  {
    Fail(file, "cannot read the size of " + what);
  }
  std::vector<std::string> out(static_cast<std::size_t>(n));
  if (n == 0)
  {
    return out;
  }
  if (H5Tis_variable_str(type) > 0)
  {
    Handle mem = Utf8VariableString();
    std::vector<char*> ptrs(static_cast<std::size_t>(n), nullptr);
    CheckStatus(
      H5Dread(dset, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), file, "cannot read " + what);
    for (std::size_t i = 0; i < out.size(); ++i)
    {
      out[i] = ptrs[i] ? ptrs[i] : "";
    }
    H5Dvlen_reclaim(mem, space, H5P_DEFAULT, ptrs.data());
  }
  else
  {
    std::size_t size = H5Tget_size(type);
    Handle mem(H5Tcopy(H5T_C_S1));
    H5Tset_size(mem, size);
    H5Tset_strpad(mem, H5T_STR_NULLPAD);
    std::vector<char> buffer(size * static_cast<std::size_t>(n));
    CheckStatus(H5Dread(dset, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
      file,
      "cannot read " + what);
    for (std::size_t i = 0; i < out.size(); ++i)
    {
      const char* s = buffer.data() + i * size;
      out[i].assign(s, strnlen(s, size));
    }
  }
  return out;
}

//------------------------------------------------------------------------------
Handle ChunkedPlist(const std::vector<hsize_t>& chunk, int deflateLevel)
{
  Handle plist(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data());
  if (deflateLevel > 0)
  {
    H5Pset_shuffle(plist);
    H5Pset_deflate(plist, static_cast<unsigned>(deflateLevel));
  }
  return plist;
}

//------------------------------------------------------------------------------
void WriteStrings(hid_t loc,
  const std::string& name,
  const std::vector<std::string>& values,
  int deflateLevel)
{
  Handle type = Utf8VariableString();
  hsize_t n = values.size();
  hsize_t maxDims = H5S_UNLIMITED;
  Handle space(H5Screate_simple(1, &n, &maxDims));
  Handle plist = ChunkedPlist({ 256 }, deflateLevel);
  Handle dset(H5Dcreate2(loc, name.c_str(), type, space, H5P_DEFAULT, plist, H5P_DEFAULT));
  if (!dset.Valid())
  {
    throw std::runtime_error("cannot create dataset " + name);
  }
  if (n == 0)
  {
    return;
  }
  std::vector<const char*> ptrs(values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    ptrs[i] = values[i].c_str();
  }
  if (H5Dwrite(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) < 0)
  {
    throw std::runtime_error("cannot write dataset " + name);
  }
}

//------------------------------------------------------------------------------
Handle CreateAndWrite(hid_t loc,
  const std::string& name,
  hid_t fileType,
  hid_t memType,
  const std::vector<hsize_t>& dims,
  const std::vector<hsize_t>& chunk,
  int deflateLevel,
  const void* data,
  const std::string& file)
{
  std::vector<hsize_t> maxDims = dims;
  maxDims[0] = H5S_UNLIMITED;
  std::vector<hsize_t> c = chunk;
  for (std::size_t i = 1; i < c.size(); ++i)
  {
    c[i] = std::max<hsize_t>(1, std::min(c[i], dims[i]));
  }
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxDims.data()));
  Handle plist = ChunkedPlist(c, deflateLevel);
  Handle dset(Check(H5Dcreate2(loc, name.c_str(), fileType, space, H5P_DEFAULT, plist, H5P_DEFAULT),
    file,
    "cannot create dataset " + name));
  if (dims[0] > 0 && data)
  {
    CheckStatus(H5Dwrite(dset, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
      file,
      "cannot write dataset " + name);
  }
  return dset;
}

//------------------------------------------------------------------------------
void Append1D(hid_t dset,
  hid_t memType,
  std::size_t n,
  const void* data,
  const std::string& file,
  const std::string& what)
{
  if (n == 0)
  {
    return;
  }
  if (Dims(dset).size() != 1)
  {
    throw std::runtime_error(file + ": " + what + " is not one-dimensional");
  }
  AppendRows(dset, memType, n, data, file, what);
}

//------------------------------------------------------------------------------
void AppendRows(hid_t dset,
  hid_t memType,
  std::size_t n,
  const void* data,
  const std::string& file,
  const std::string& what)
{
  if (n == 0)
  {
    return;
  }
  std::vector<hsize_t> dims = Dims(dset);
  if (dims.empty())
  {
    throw std::runtime_error(file + ": " + what + " is a scalar");
  }
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = dims[0];
  count[0] = n;
  dims[0] += n;
  CheckStatus(H5Dset_extent(dset, dims.data()), file, "cannot extend " + what);
  Handle fileSpace(H5Dget_space(dset));
  H5Sselect_hyperslab(fileSpace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  Handle memSpace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr));
  CheckStatus(H5Dwrite(dset, memType, memSpace, fileSpace, H5P_DEFAULT, data),
    file,
    "cannot append to " + what);
}

//------------------------------------------------------------------------------
void ReadAll(hid_t dset, hid_t memType, void* out, const std::string& file, const std::string& what)
{
  CheckStatus(
    H5Dread(dset, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), file, "cannot read " + what);
}

} // namespace h5
} // namespace vis4gs
