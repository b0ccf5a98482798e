#pragma once
/// @file CliErrors.h
/// Exit codes shared by every `buoyancy` subcommand, and the exception that carries a usage error.

#include <stdexcept>

namespace buoyancy::cli {

/// Exit codes of every subcommand.
enum ExitCode : int {
    kExitOk = 0,        ///< success (warnings go to stderr)
    kExitBadInput = 2,  ///< bad input or usage: unknown flag, unreadable mesh, invalid scene key, …
    kExitInternal = 3,  ///< an internal failure that should never happen (e.g. a non-finite result)
};

/// Bad input or usage; what() is the message printed on stderr (exit 2).
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A result that should never happen, such as a non-finite number (exit 3).
class InternalError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace buoyancy::cli
