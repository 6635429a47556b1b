// [devices.*] tables: every backend's settings reach the device configs, mistakes name file, line and key,
// and the generated systemd drop-in opens exactly the configured devices and verifies cleanly.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "firmware-host/kiosk_config.hpp"
#include "firmware-host/unit_dropin.hpp"
#include "model/error.hpp"

namespace walk::kiosk {
namespace device_config_test {  // named, not anonymous: the suite compiles as unity batches

namespace fs = std::filesystem;

class DeviceConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("walk_devcfg_" + std::to_string(getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& devices) {
    const auto path = (dir_ / "kiosk.toml").string();
    std::ofstream(path) << "bundle = \"x.walk\"\n[start]\nx = 0\ny = 0\n" << devices;
    return path;
  }
  std::string error(const std::string& devices) {
    try {
      (void)load_kiosk_config(write(devices));
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(DeviceConfigTest, HardwareExampleReadsEveryBackend) {
  const auto c = load_kiosk_config(WALK_SOURCE_DIR "/config/kiosk/hardware.toml");
  ASSERT_TRUE(c.devices.treadmill && c.devices.head_tracker && c.devices.buttons && c.devices.dimmer_panel);
  const auto& t = c.devices.treadmill->hid;
  EXPECT_EQ(t.path, "/dev/walk-treadmill");
  ASSERT_EQ(t.layout.report_id, std::optional<std::uint8_t>(1));
  EXPECT_EQ(t.layout.fields.size(), 2u);
  EXPECT_TRUE(t.layout.fields[1].is_signed);
  EXPECT_NEAR(t.layout.fields[1].scale, 0.1 * std::numbers::pi / 180.0, 1e-12);  // degrees -> radians
  EXPECT_NEAR(t.layout.fields[1].max, std::numbers::pi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(t.faults.stale_after, 0.25);
  EXPECT_FALSE(c.devices.head_tracker->hid.layout.report_id);
  const auto& b = c.devices.buttons->buttons;
  EXPECT_EQ(b.lines.size(), 2u);
  EXPECT_DOUBLE_EQ(b.debounce, 0.02);
  const auto& m = c.devices.dimmer_panel->modbus;
  EXPECT_EQ(m.host, "192.168.10.20");
  EXPECT_EQ(m.registers, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_DOUBLE_EQ(m.timeout, 0.1);
  EXPECT_EQ(m.retries, 2);
  EXPECT_DOUBLE_EQ(m.poll_hz, 20.0);
}

TEST_F(DeviceConfigTest, RtuAndGpioEncoder) {
  const auto c = load_kiosk_config(write(R"(
[devices.treadmill]
backend = "gpio"
chip = "gpiochip1"
line = 17
metres_per_pulse = 0.005
debounce_ms = 0.25
[devices.dimmer_panel]
backend = "modbus"
transport = "rtu"
device = "/dev/ttyUSB0"
baud = 38400
parity = "N"
registers = [10, 11]
function = "input"
)"));
  EXPECT_EQ(c.devices.treadmill->encoder.line, 17u);
  EXPECT_DOUBLE_EQ(c.devices.treadmill->encoder.debounce, 0.00025);
  const auto& m = c.devices.dimmer_panel->modbus;
  EXPECT_EQ(m.transport, devices::ModbusPanelConfig::Transport::Rtu);
  EXPECT_EQ(m.parity, 'N');
  EXPECT_TRUE(m.input_registers);
}

TEST_F(DeviceConfigTest, DefaultsComputedFromOtherKeysAreFittedNotReportedAsMistakes) {
  // retry_min above retry_max's default, with retry_max not written: retry_max follows it.
  const std::string slow_retry = error(
      "[devices.treadmill]\nbackend = \"hid\"\npath = \"/dev/x\"\nretry_min = 10\n"
      "report = { length = 3, fields = [{ name = \"speed\", offset = 1, size = 2 }] }\n");
  EXPECT_EQ(slow_retry, "") << slow_retry;
  // A slow panel whose derived stale_after would pass 3600 s: fitted, not blamed on a key never written.
  const std::string slow_panel = error(
      "[devices.dimmer_panel]\nbackend = \"modbus\"\nregisters = [0]\n"
      "host = \"127.0.0.1\"\npoll_hz = 0.1\ntimeout_ms = 60000\nretries = 100\n");
  EXPECT_EQ(slow_panel, "") << slow_panel;
  // Written out of range, it is still the user's mistake.
  const std::string written = error(
      "[devices.treadmill]\nbackend = \"hid\"\npath = \"/dev/x\"\nretry_min = 10\n"
      "retry_max = 5\nreport = { length = 3, fields = [{ name = \"speed\", offset = 1, size = 2 }] }\n");
  EXPECT_NE(written.find("retry_max"), std::string::npos) << written;
}

TEST_F(DeviceConfigTest, ReportLayoutsSayWhatIsMissingOrImpossible) {
  const std::string no_length = error(
      "[devices.treadmill]\nbackend = \"hid\"\npath = \"/dev/x\"\n"
      "[devices.treadmill.report]\nfields = [{ name = \"speed\", size = 2 }]\n");
  EXPECT_NE(no_length.find("key 'devices.treadmill.report': missing key 'length'"), std::string::npos)
      << no_length;
  const std::string three = error(
      "[devices.treadmill]\nbackend = \"hid\"\npath = \"/dev/x\"\n"
      "[devices.treadmill.report]\nlength = 4\nfields = [{ name = \"speed\", size = 3 }]\n");
  EXPECT_NE(three.find("fields[0].size': must be 1, 2 or 4 bytes"), std::string::npos) << three;
}

TEST_F(DeviceConfigTest, MistakesNameTheKeyAndLine) {
  EXPECT_NE(error("[devices.dimmer_panel]\nbackend = \"hid\"\npath = \"/dev/x\"\n")
                .find("devices.dimmer_panel.backend"),
            std::string::npos);
  EXPECT_NE(error("[devices.treadmill]\nbackend = \"hid\"\npath = "
                  "\"/dev/x\"\n[devices.treadmill.report]\nlength = 2\n"
                  "fields = [{ name = \"speed\", offset = 1, size = 2 }]\n")
                .find("past the report length"),
            std::string::npos);
  EXPECT_NE(error("[devices.dimmer_panel]\nbackend = \"modbus\"\nregisters = [0]\ntransport = \"udp\"\n")
                .find("kiosk.toml:8: key 'devices.dimmer_panel.transport': unknown transport"),
            std::string::npos)
      << error("[devices.dimmer_panel]\nbackend = \"modbus\"\nregisters = [0]\ntransport = \"udp\"\n");
  EXPECT_NE(
      error("[devices.buttons]\nbackend = \"gpio\"\nchip = \"gpiochip0\"\nlines = { self_destruct = 3 }\n")
          .find("unknown button"),
      std::string::npos);
  EXPECT_NE(error("[devices.treadmill]\nbackend = \"hid\"\npath = \"/dev/x\"\nreport = { length = 3, fields "
                  "= [{ name = "
                  "\"speed\", offset = 1, size = 2, sined = true }] }\n")
                .find("sined"),
            std::string::npos);
}

TEST_F(DeviceConfigTest, DropinAllowsOnlyTheConfiguredDevicesAndNetworkOnlyForModbusTcp) {
  const auto hw = load_kiosk_config(WALK_SOURCE_DIR "/config/kiosk/hardware.toml");
  const std::string d = unit_dropin(hw);
  EXPECT_NE(d.find("DeviceAllow=/dev/walk-treadmill rw"), std::string::npos) << d;
  EXPECT_NE(d.find("DeviceAllow=/dev/walk-head rw"), std::string::npos) << d;
  EXPECT_NE(d.find("DeviceAllow=/dev/gpiochip0 rw"), std::string::npos) << d;
  EXPECT_NE(d.find("IPAddressAllow=192.168.10.20"), std::string::npos) << d;
  EXPECT_NE(d.find("PrivateNetwork=no"), std::string::npos) << d;

  const auto mock = load_kiosk_config(WALK_SOURCE_DIR "/config/kiosk/demo.toml");
  const std::string m = unit_dropin(mock);
  EXPECT_EQ(m.find("DeviceAllow"), std::string::npos) << m;
  EXPECT_EQ(m.find("AF_INET"), std::string::npos) << m;  // no network without Modbus TCP

  const auto rtu =
      load_kiosk_config(write("[devices.dimmer_panel]\nbackend = \"modbus\"\ntransport = \"rtu\"\n"
                              "device = \"/dev/ttyUSB0\"\nregisters = [0]\n"));
  const std::string r = unit_dropin(rtu);
  EXPECT_NE(r.find("DeviceAllow=/dev/ttyUSB0 rw"), std::string::npos) << r;
  EXPECT_EQ(r.find("AF_INET"), std::string::npos) << r;

  if (std::system("command -v systemd-analyze >/dev/null 2>&1") != 0) GTEST_SKIP() << "no systemd-analyze";
  for (const auto* text : {&d, &r}) {
    const auto file = dir_ / "devices.conf";
    std::ofstream(file) << *text;
    const auto log = dir_ / "verify.log";
    const std::string cmd =
        "sh " WALK_SOURCE_DIR "/systemd/verify-unit.sh '' " + file.string() + " > " + log.string() + " 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream in(log);
    std::stringstream out;
    out << in.rdbuf();
    EXPECT_EQ(rc, 0) << out.str();
    EXPECT_EQ(out.str().find("FAIL"), std::string::npos) << out.str();
  }
}

}  // namespace device_config_test
}  // namespace walk::kiosk
