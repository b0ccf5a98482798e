#pragma once
/// @file Progress.h
/// Progress of a long command on stderr: a bar with the elapsed time and an estimate of the time left when stderr
/// is a terminal (redrawn at most 10 times a second), a plain line every 10 % or every 30 s otherwise (logs, CI),
/// nothing when quiet.

#include <chrono>
#include <cstdio>
#include <string>

namespace buoyancy::cli {

/// One progress report, from 0 to `total` units of work.
class ProgressReporter {
public:
    /// How the progress is shown.
    enum class Mode {
        Quiet,     ///< nothing
        Terminal,  ///< a bar redrawn in place (\r)
        Lines,     ///< a line every 10 % or 30 s
    };

    /// The mode for stderr: Terminal when it is a terminal, Lines otherwise, Quiet when `quiet`.
    static Mode modeForStderr(bool quiet);

    /// @param label  what runs, e.g. "run boat.json"
    /// @param total  units of work in all (> 0), e.g. simulated seconds
    /// @param unit   how a unit is written after the numbers, e.g. " s simulated" ("" = percent only)
    ProgressReporter(std::string label, double total, std::string unit, Mode mode, std::FILE* out = stderr);

    /// Report that `done` units (0 ≤ done ≤ total) are done.
    void update(double done);

    /// The last report (100 %) and a newline after a bar; safe to call twice.
    void finish();

    /// Seconds since construction.
    double elapsedSeconds() const;

    /// "12 s", "3 min 05 s", "1 h 02 min": a duration for people.
    static std::string formatDuration(double seconds);

private:
    void print(double done, bool final);

    std::string m_label, m_unit;
    double m_total;
    Mode m_mode;
    std::FILE* m_out;
    std::chrono::steady_clock::time_point m_start, m_lastPrint;
    int m_lastDecile = 0;
    bool m_finished = false;
    bool m_printedBar = false;
};

}  // namespace buoyancy::cli
