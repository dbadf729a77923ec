// Small helpers shared by test files.
#pragma once
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

// The real game dumps (../shared/frametests/dumps), sorted; empty when the folder is absent.
inline std::vector<std::string> frametestDumps() {
    std::vector<std::string> out;
    std::filesystem::path dir = std::filesystem::path(GE2GL_FRAMETESTS_DIR) / "dumps";
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return out;
    for (auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path().string());
    std::sort(out.begin(), out.end());
    return out;
}
