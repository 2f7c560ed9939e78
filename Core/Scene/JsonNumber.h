// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file JsonNumber.h
 * @brief Internal to the JSON camera readers (CameraJson.cxx, TransformsJson.cxx): a finite
 * number or a std::runtime_error naming the file and the place.
 */
#ifndef vis4gs_JsonNumber_h
#define vis4gs_JsonNumber_h

#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace vis4gs
{
namespace detail
{

inline double JsonNumber(const nlohmann::json& j, const std::string& name, const std::string& where)
{
  if (!j.is_number())
  {
    throw std::runtime_error(name + ": " + where + " is not a number");
  }
  const double v = j.get<double>();
  if (!std::isfinite(v))
  {
    throw std::runtime_error(name + ": " + where + " is not finite");
  }
  return v;
}

} // namespace detail
} // namespace vis4gs

#endif
