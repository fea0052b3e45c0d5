#include "runtime/log_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "common/core/io_error.hpp"

namespace ltm::runtime {
namespace {
namespace fs = std::filesystem;
std::string rotated(const std::string& file, int i) { return file + "." + std::to_string(i); }
}  // namespace

RotatingLogFile::RotatingLogFile(HostLogConfig config) : config_(std::move(config)) {
    max_bytes_ = static_cast<std::uint64_t>(config_.max_mb * (1 << 20));
    if (max_bytes_ < 1024) max_bytes_ = 1024;
    std::error_code ec;
    const fs::path parent = fs::path(config_.file).parent_path();
    if (!parent.empty()) fs::create_directories(parent, ec);
    if (ec) throw common::IoError(config_.file, "cannot create its folder: " + ec.message());
    if (!open())
        throw common::IoError(config_.file, std::string("cannot open: ") + std::strerror(errno));
}

RotatingLogFile::~RotatingLogFile() {
    if (out_) std::fclose(out_);
}

bool RotatingLogFile::open() {
    out_ = std::fopen(config_.file.c_str(), "a");
    if (!out_) return false;
    std::error_code ec;
    const auto size = fs::file_size(config_.file, ec);
    size_ = ec ? 0 : size;
    return true;
}

void RotatingLogFile::rotate() {
    if (out_) std::fclose(out_);
    out_ = nullptr;
    std::error_code ec;
    if (config_.keep <= 0) {
        fs::remove(config_.file, ec);
    } else {
        fs::remove(rotated(config_.file, config_.keep), ec);
        for (int i = config_.keep - 1; i >= 1; --i)
            if (fs::exists(rotated(config_.file, i), ec))
                fs::rename(rotated(config_.file, i), rotated(config_.file, i + 1), ec);
        fs::rename(config_.file, rotated(config_.file, 1), ec);
    }
    open();
}

std::string RotatingLogFile::write(const std::string& line) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (size_ > 0 && size_ + line.size() > max_bytes_) rotate();
    bool ok = out_ != nullptr;
    const char* why = "cannot open the file";
    if (ok &&
        (std::fwrite(line.data(), 1, line.size(), out_) != line.size() || std::fflush(out_) != 0)) {
        ok = false;
        why = std::strerror(errno);
        // A line half written stays half: the next one starts on a line of its own.
        std::clearerr(out_);
        std::fclose(out_);
        out_ = nullptr;
        std::error_code ec;
        fs::resize_file(config_.file, size_, ec);
    }
    if (!ok) {
        if (!out_) open();
        ++refused_;
        if (failing_) return "";
        failing_ = true;
        return "host log " + config_.file + ": " + why +
               "; its lines go to stderr only until it takes them again";
    }
    size_ += line.size();
    if (!failing_) return "";
    failing_ = false;
    const std::string note = "host log " + config_.file + " takes lines again (" +
                             std::to_string(refused_) + " lines missing from it)";
    refused_ = 0;
    return note;
}

}  // namespace ltm::runtime
