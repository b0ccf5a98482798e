#include "browser/BrowserOptions.h"

#include <stdexcept>
#include <string>

namespace buoyancy::browser {

namespace {
int integer(const std::string& flag, const char* text, int lo, int hi) {
    std::size_t used = 0;
    int v = 0;
    try {
        v = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || text[used] != '\0' || v < lo || v > hi)
        throw std::invalid_argument(flag + ": expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                    "], got \"" + text + "\"");
    return v;
}
}  // namespace

const char* browserUsage() {
    return "usage: buoyancy_browser [--scene NAME|NUMBER] [--size W H] [--screenshot FILE --frames N] [--list] [--help]\n"
           "  --scene NAME|NUMBER  the scene to open first: its name or its number 1..N (--list prints both)\n"
           "  --size W H           window size in pixels (default 1280 720)\n"
           "  --screenshot FILE    render N frames (--frames, default 60) at 1/60 s each, save the window as a PNG\n"
           "                       and exit (under Xvfb: xvfb-run -a buoyancy_browser ...)\n"
           "  --list               print the scenes, numbered, and exit\n"
           "  --help               print this and exit\n";
}

BrowserOptions parseBrowserOptions(int argc, char** argv) {
    BrowserOptions o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto need = [&](int n) {
            if (i + n >= argc) throw std::invalid_argument(a + ": missing value");
        };
        if (a == "--scene") {
            need(1);
            o.scene = argv[++i];
        } else if (a == "--size") {
            need(2);
            o.width = integer(a, argv[++i], 320, 8192);
            o.height = integer(a, argv[++i], 240, 8192);
        } else if (a == "--screenshot") {
            need(1);
            o.screenshot = argv[++i];
        } else if (a == "--frames") {
            need(1);
            o.frames = integer(a, argv[++i], 1, 1000000);
        } else if (a == "--list") {
            o.list = true;
        } else if (a == "--help" || a == "-h") {
            o.help = true;
        } else {
            throw std::invalid_argument("unknown option \"" + a + "\" (--scene, --size, --screenshot, --frames, --list)");
        }
    }
    return o;
}

}  // namespace buoyancy::browser
