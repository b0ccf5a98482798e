#include "cli/Progress.h"

#include <algorithm>
#include <cmath>
#include <unistd.h>

namespace buoyancy::cli {

ProgressReporter::Mode ProgressReporter::modeForStderr(bool quiet) {
    if (quiet) return Mode::Quiet;
    return isatty(STDERR_FILENO) ? Mode::Terminal : Mode::Lines;
}

ProgressReporter::ProgressReporter(std::string label, double total, std::string unit, Mode mode, std::FILE* out)
    : m_label(std::move(label)), m_unit(std::move(unit)), m_total(total > 0 ? total : 1.0), m_mode(mode), m_out(out),
      m_start(std::chrono::steady_clock::now()), m_lastPrint(m_start) {}

double ProgressReporter::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

std::string ProgressReporter::formatDuration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    char buf[64];
    const long s = std::lround(seconds);
    if (s < 60) std::snprintf(buf, sizeof buf, "%ld s", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
    else std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
    return buf;
}

void ProgressReporter::update(double done) {
    if (m_mode == Mode::Quiet || m_finished) return;
    done = std::clamp(done, 0.0, m_total);
    const auto now = std::chrono::steady_clock::now();
    const double sinceLast = std::chrono::duration<double>(now - m_lastPrint).count();
    if (m_mode == Mode::Terminal) {
        if (sinceLast < 0.1) return;
    } else {
        const int decile = static_cast<int>(std::floor(10.0 * done / m_total));
        if (decile <= m_lastDecile && sinceLast < 30.0) return;
        m_lastDecile = std::max(m_lastDecile, decile);
    }
    m_lastPrint = now;
    print(done, false);
}

void ProgressReporter::finish() {
    if (m_mode == Mode::Quiet || m_finished) return;
    m_finished = true;
    if (m_mode == Mode::Lines && m_lastDecile >= 10) return;  // the 100 % line is out already
    print(m_total, true);
}

void ProgressReporter::print(double done, bool final) {
    const double elapsed = elapsedSeconds();
    const double fraction = done / m_total;
    std::string eta = "?";
    if (final) eta = "0 s";
    else if (fraction > 0.0) eta = formatDuration(elapsed * (1.0 - fraction) / fraction);
    char amount[96] = "";
    if (!m_unit.empty()) std::snprintf(amount, sizeof amount, " (%.4g of %.4g%s)", done, m_total, m_unit.c_str());
    if (m_mode == Mode::Terminal) {
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(std::lround(fraction * kWidth));
        std::string bar(static_cast<std::size_t>(filled), '#');
        bar.append(static_cast<std::size_t>(kWidth - filled), '.');
        std::fprintf(m_out, "\r%s [%s] %3.0f %%%s  elapsed %s  left %s\x1b[K", m_label.c_str(), bar.c_str(),
                     100.0 * fraction, amount, formatDuration(elapsed).c_str(), eta.c_str());
        if (final) std::fputc('\n', m_out);
        m_printedBar = true;
    } else {
        std::fprintf(m_out, "%s: %3.0f %%%s, elapsed %s, left %s\n", m_label.c_str(), 100.0 * fraction, amount,
                     formatDuration(elapsed).c_str(), eta.c_str());
    }
    std::fflush(m_out);
}

}  // namespace buoyancy::cli
