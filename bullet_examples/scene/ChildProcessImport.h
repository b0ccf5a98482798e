#pragma once
/// @file ChildProcessImport.h
/// Run assimp (buoyancy::importMeshFile) in a forked child process with a time limit, so that a file on
/// which the importer crashes or hangs becomes a clear MeshError instead of taking the program down
/// ("the CLI imports in a child process with a time limit"). POSIX only (fork, pipe, poll).
/// Call it while the process is single-threaded: after fork() only async-signal-safe work is strictly
/// allowed in a multithreaded parent, and the child here runs the whole importer.

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <string>
#include <vector>

namespace buoyancy::cli {

/// Import `path` like buoyancy::importMeshFile(path, scale, warnings), but in a child process.
/// The child sends the triangle soup (or the error text) back through a pipe; the parent reads while
/// the child writes (no deadlock on large meshes) and enforces the deadline.
/// @param[in] path  mesh file (allow-list of supportedMeshExtensions())
/// @param[in] scale  uniform scale applied after the node transforms (> 0)
/// @param[in] timeoutSeconds  wall-clock limit for the whole import, s (CLI default 10)
/// @param[out] warnings  when not null, receives the importer's warnings
/// @throws buoyancy::MeshError "FILE: ..." for every failure of the import itself, and also
///         "FILE: import timed out after T s" (the child is killed) and
///         "FILE: importer crashed (signal N)".
buoyancy::TriangleMesh importMeshInChildProcess(const std::string& path, double scale, double timeoutSeconds,
                                                std::vector<buoyancy::MeshWarning>* warnings = nullptr);

/// TEST ONLY: a fault the *child* injects before importing, to test the timeout and crash paths.
enum class ChildImportTestFault {
    None,   ///< normal operation (the default; never change it outside tests)
    Crash,  ///< the child raises SIGSEGV
    Hang,   ///< the child sleeps forever
};
/// TEST ONLY: set the fault injected by the next child imports (process-wide).
void setChildImportTestFaultForTesting(ChildImportTestFault fault);

}  // namespace buoyancy::cli
