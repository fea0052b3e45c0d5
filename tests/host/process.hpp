#pragma once
// Runs a program as a child process for end-to-end tests: stderr and stdout to files, a timeout,
// signals.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace ltm::tests {

class Process {
  public:
    Process(const std::vector<std::string>& argv, const std::string& log_prefix)
        : log_(log_prefix) {
        pid_ = fork();
        if (pid_ == 0) {
            const int err = open((log_ + ".err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int out = open((log_ + ".out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            dup2(err, 2);
            dup2(out, 1);
            std::vector<char*> args;
            for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
            args.push_back(nullptr);
            execv(args[0], args.data());
            _exit(127);
        }
        start_ = std::chrono::steady_clock::now();
    }
    ~Process() {
        if (pid_ > 0 && !exited_) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
    }
    void signal(int sig) { kill(pid_, sig); }
    pid_t pid() const { return pid_; }
    // Exit code (128 + signal when killed); -1 when still running after `timeout_s` (then killed).
    int wait(double timeout_s) {
        const auto deadline =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (std::chrono::steady_clock::now() < deadline) {
            int status = 0;
            if (waitpid(pid_, &status, WNOHANG) == pid_) {
                exited_ = true;
                end_ = std::chrono::steady_clock::now();
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        exited_ = true;
        return -1;
    }
    double seconds_since_start() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    std::string err() const { return read(log_ + ".err"); }
    // Waits until the log (stderr) holds `text` (true), or `timeout_s` from now (false): a
    // generous bound, never a timing assertion.
    bool wait_for_log(const std::string& text, double timeout_s) const {
        const auto deadline =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (std::chrono::steady_clock::now() < deadline) {
            if (err().find(text) != std::string::npos) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        return false;
    }
    std::string out() const { return read(log_ + ".out"); }

    static std::string read(const std::string& path) {
        std::ifstream in(path);
        std::stringstream ss;
        ss << in.rdbuf();
        return ss.str();
    }

  private:
    pid_t pid_ = -1;
    bool exited_ = false;
    std::string log_;
    std::chrono::steady_clock::time_point start_, end_;
};

}  // namespace ltm::tests
