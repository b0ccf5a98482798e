// buoyancy_browser: the scene browser app. See browser/BrowserOptions.h for the command line.

#include "browser/BrowserApp.h"
#include "browser/BrowserOptions.h"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
    using namespace buoyancy::browser;
    BrowserOptions options;
    try {
        options = parseBrowserOptions(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << '\n';
        std::cerr << browserUsage();
        return 2;
    }
    if (options.help) {
        std::cout << browserUsage();
        return 0;
    }
    return runBrowser(options);
}
