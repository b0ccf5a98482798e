#pragma once
/// @file SceneJsonReader.h
/// The strict JSON reader every part of a scene file is read with (world, bodies, water, water graph): each
/// accessor checks type and range and, on failure, reports the full key path ("bodies[0].shape.size[1]: value -1
/// out of range ...") through one fail function, so every error names its key.

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <initializer_list>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

namespace buoyancy::cli {

/// Reports a bad value: key path and what is wrong. Must throw (never return).
using SceneFailFn = std::function<void(const std::string& key, const std::string& what)>;

/// Strict accessors over nlohmann::json; every failure goes through the fail function.
class SceneJsonReader {
public:
    using json = nlohmann::json;

    /// @param fail  called with the key path and the problem; must throw
    explicit SceneJsonReader(SceneFailFn fail) : m_fail(std::move(fail)) {}

    /// Report a bad value (throws through the fail function).
    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        m_fail(key, what);
        throw std::logic_error("SceneJsonReader: the fail function returned");  // never reached
    }

    /// "parent.key", or "key" at the top level.
    static std::string join(const std::string& parent, const std::string& key) {
        return parent.empty() ? key : parent + "." + key;
    }

    /// The value must be an object.
    void requireObject(const json& j, const std::string& key) const {
        if (!j.is_object()) fail(key.empty() ? "(top level)" : key, "expected an object");
    }

    /// Every key of the object must be in `allowed`.
    void allowKeys(const json& j, const std::string& key, std::initializer_list<const char*> allowed) const {
        const std::set<std::string> ok(allowed.begin(), allowed.end());
        for (auto it = j.begin(); it != j.end(); ++it)
            if (!ok.count(it.key())) fail(join(key, it.key()), "unknown key");
    }

    /// A finite number in [lo, hi] (strict lower bound when lowOpen).
    double number(const json& j, const std::string& key, double lo, double hi, bool lowOpen = false) const {
        if (!j.is_number()) fail(key, "expected a number");
        const double v = j.get<double>();
        if (!std::isfinite(v) || (lowOpen ? !(v > lo) : !(v >= lo)) || !(v <= hi)) {
            std::ostringstream os;
            os << "value " << v << " out of range " << (lowOpen ? "(" : "[") << lo << ", " << hi << "]";
            fail(key, os.str());
        }
        return v;
    }

    /// An integer in [lo, hi].
    int integer(const json& j, const std::string& key, long long lo, long long hi) const {
        if (!j.is_number_integer() && !j.is_number_unsigned()) fail(key, "expected an integer");
        const long long v = j.get<long long>();
        if (v < lo || v > hi)
            fail(key, "value " + std::to_string(v) + " out of range [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "]");
        return int(v);
    }

    /// Three numbers, each in [lo, hi].
    Eigen::Vector3d vec3(const json& j, const std::string& key, double lo = -1e9, double hi = 1e9,
                         bool lowOpen = false) const {
        if (!j.is_array() || j.size() != 3) fail(key, "expected an array of 3 numbers");
        Eigen::Vector3d v;
        for (int k = 0; k < 3; ++k) v[k] = number(j[k], key + "[" + std::to_string(k) + "]", lo, hi, lowOpen);
        return v;
    }

    /// A string.
    std::string string(const json& j, const std::string& key) const {
        if (!j.is_string()) fail(key, "expected a string");
        return j.get<std::string>();
    }

    /// true or false.
    bool boolean(const json& j, const std::string& key) const {
        if (!j.is_boolean()) fail(key, "expected true or false");
        return j.get<bool>();
    }

private:
    SceneFailFn m_fail;
};

}  // namespace buoyancy::cli
