// walkd under a pretend systemd: NOTIFY_SOCKET and WATCHDOG_USEC set, messages read back from the socket.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test_bundle.hpp"

namespace sd_notify_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

TEST(WalkdNotify, SendsReadyWatchdogStatusAndStopping) {
  const std::string walkd = WALK_BINARY_DIR "/firmware-host/walkd";
  if (!fs::exists(walkd)) GTEST_SKIP() << "walkd not built";
  const auto dir = fs::temp_directory_path() / "walk_notify_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto bundle = walk::kiosk::testing::write_two_room_bundle((dir / "rooms.walk").string());
  std::ofstream(dir / "kiosk.toml")
      << "bundle = \"rooms.walk\"\n[display]\nwidth = 64\nheight = 36\n"
      << "[start]\nx = 102\ny = 202\nfloor_z = 10\n"
      // A panel nobody answers for: walkd runs on and reports it down.
      << "[devices.dimmer_panel]\nbackend = \"modbus\"\nport = 1\nregisters = [0]\n";

  const std::string socket_path = (dir / "notify.sock").string();
  const int sock = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(sock, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.size(), sizeof addr.sun_path);
  std::copy(socket_path.begin(), socket_path.end(), addr.sun_path);
  ASSERT_EQ(bind(sock, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);

  // Drain the socket while walkd runs: a full datagram queue would block its sd_notify calls.
  timeval timeout{0, 100000};
  setsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  const std::string log = (dir / "walkd.log").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    setenv("NOTIFY_SOCKET", socket_path.c_str(), 1);
    setenv("WATCHDOG_USEC", "2000000", 1);
    const std::string config = (dir / "kiosk.toml").string(), out = (dir / "out").string();
    if (!std::freopen(log.c_str(), "w", stdout) || !std::freopen(log.c_str(), "a", stderr)) _exit(126);
    execl(walkd.c_str(), "walkd", "--config", config.c_str(), "--simulate", "1", "--output", out.c_str(),
          nullptr);
    _exit(127);
  }
  // The reader starts after fork so the child never inherits a thread's half-held locks.
  std::vector<std::string> messages;
  std::atomic<bool> child_done{false};
  std::thread reader([&] {
    char buf[4096];
    while (true) {
      const ssize_t n = recv(sock, buf, sizeof buf, 0);
      if (n > 0)
        messages.emplace_back(buf, static_cast<std::size_t>(n));
      else if (child_done)
        return;
    }
  });

  int status = 0;
  waitpid(pid, &status, 0);
  child_done = true;
  reader.join();
  close(sock);
  std::ifstream log_in(log);
  std::stringstream log_text;
  log_text << log_in.rdbuf();
  if (WIFEXITED(status) && WEXITSTATUS(status) == 1 && log_text.str().find("backend") != std::string::npos)
    GTEST_SKIP() << "no GL backend here: " << log_text.str();
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << log_text.str();

  fs::remove_all(dir);

  ASSERT_FALSE(messages.empty());
  EXPECT_EQ(messages.front(), "READY=1");
  const auto count = [&](const std::string& prefix) {
    return std::count_if(messages.begin(), messages.end(),
                         [&](const auto& m) { return m.rfind(prefix, 0) == 0; });
  };
  EXPECT_EQ(count("READY=1"), 1);
  EXPECT_EQ(count("WATCHDOG=1"), 30);  // one per frame: 1 s at 30 Hz
  EXPECT_GE(count("STATUS="), 1);
  EXPECT_EQ(messages.back(), "STOPPING=1");
  const auto status_it = std::find_if(messages.begin(), messages.end(),
                                      [](const auto& m) { return m.rfind("STATUS=", 0) == 0; });
  EXPECT_NE(status_it->find("fps"), std::string::npos) << *status_it;
  EXPECT_NE(status_it->find("room A"), std::string::npos) << *status_it;
  EXPECT_NE(status_it->find("dimmer_panel down"), std::string::npos) << *status_it;
}

}  // namespace sd_notify_test
