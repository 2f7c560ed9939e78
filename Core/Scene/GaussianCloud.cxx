// SPDX-License-Identifier: BSD-3-Clause
#include "GaussianCloud.h"

#include <cstring>

namespace vis4gs
{

//------------------------------------------------------------------------------
std::size_t ScalarTypeSize(ScalarType type)
{
  switch (type)
  {
    case ScalarType::Int8:
    case ScalarType::UInt8:
      return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16:
      return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32:
      return 4;
    case ScalarType::Float64:
      return 8;
  }
  return 0;
}

//------------------------------------------------------------------------------
namespace
{
template <typename T>
double Load(const unsigned char* p)
{
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}
}

//------------------------------------------------------------------------------
double ExtraProperty::GetAsDouble(std::size_t i) const
{
  const unsigned char* p = this->Bytes.data() + i * ScalarTypeSize(this->Type);
  switch (this->Type)
  {
    case ScalarType::Int8:
      return Load<std::int8_t>(p);
    case ScalarType::UInt8:
      return Load<std::uint8_t>(p);
    case ScalarType::Int16:
      return Load<std::int16_t>(p);
    case ScalarType::UInt16:
      return Load<std::uint16_t>(p);
    case ScalarType::Int32:
      return Load<std::int32_t>(p);
    case ScalarType::UInt32:
      return Load<std::uint32_t>(p);
    case ScalarType::Float32:
      return Load<float>(p);
    case ScalarType::Float64:
      return Load<double>(p);
  }
  return 0.0;
}

//------------------------------------------------------------------------------
void GaussianCloud::Resize(std::size_t n, int shDegree)
{
  this->Count = n;
  this->ShDegree = shDegree;
  this->Positions.assign(3 * n, 0.0f);
  this->LogScales.assign(3 * n, 0.0f);
  this->Rotations.assign(4 * n, 0.0f);
  this->OpacityLogits.assign(n, 0.0f);
  this->SH.assign(3 * n * static_cast<std::size_t>(this->ShCoefficientCount()), 0.0f);
  this->Extra.clear();
}

//------------------------------------------------------------------------------
const ExtraProperty* GaussianCloud::FindExtra(const std::string& name) const
{
  for (const auto& e : this->Extra)
  {
    if (e.Name == name)
    {
      return &e;
    }
  }
  return nullptr;
}

} // namespace vis4gs
