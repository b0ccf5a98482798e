#pragma once
/// @file NumberFormat.h
/// How the tools write numbers: CSV and JSON values in the shortest decimal form that reads back to the same
/// double (std::to_chars), and never a negative zero (−0 is written as 0 everywhere).

#include <nlohmann/json.hpp>

#include <charconv>
#include <string>
#include <system_error>

namespace buoyancy::cli {

/// x with a negative zero turned into +0 (every other value unchanged; x + 0.0 is −0 only when x is −0 and the
/// rounding mode is towards −∞, which the tools never set).
inline double withoutNegativeZero(double x) { return x == 0.0 ? 0.0 : x; }

/// x for printing with `decimals` digits after the point: a value that would print as "-0.00" prints as "0.00".
inline double forFixedDecimals(double x, int decimals) {
    double half = 0.5;
    for (int i = 0; i < decimals; ++i) half *= 0.1;
    return x > -half && x < half ? 0.0 : x;
}

/// The shortest decimal text that reads back to exactly x ("0.1", not "0.10000000000000001"); −0 gives "0".
/// Non-finite values give "nan", "inf" or "-inf".
inline std::string shortestDecimal(double x) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, withoutNegativeZero(x));
    if (r.ec != std::errc()) return std::to_string(x);  // cannot happen with 64 characters
    return std::string(buf, r.ptr);
}

/// Append the shortest decimal text of x to `out` (no allocation beyond the string's own growth).
inline void appendShortestDecimal(std::string& out, double x) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, withoutNegativeZero(x));
    out.append(buf, r.ec == std::errc() ? r.ptr : buf);
}

/// Every floating-point number of a JSON document with its negative zeros turned into +0, recursively.
inline void removeNegativeZeros(nlohmann::json& j) {
    if (j.is_number_float()) {
        j = withoutNegativeZero(j.get<double>());
    } else if (j.is_structured()) {
        for (auto& child : j) removeNegativeZeros(child);
    }
}

}  // namespace buoyancy::cli
