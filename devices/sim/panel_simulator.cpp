#include "devices/sim/panel_simulator.hpp"

#include <arpa/inet.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "model/error.hpp"

namespace walk::devices {
namespace {

constexpr int kSliceUsec = 20000;  // select() slice: how quickly stop() is noticed

bool readable(int fd, fd_set& set, int max_fd) {
  timeval tv{0, kSliceUsec};
  const int r = select(max_fd + 1, &set, nullptr, nullptr, &tv);
  return r > 0 && fd >= 0;
}

}  // namespace

std::unique_ptr<PanelSimulator> PanelSimulator::tcp(const std::string& host, int port, int registers,
                                                    int slave) {
  std::unique_ptr<PanelSimulator> s(new PanelSimulator);
  s->ctx_ = modbus_new_tcp(host.c_str(), port);
  s->map_ = modbus_mapping_new(0, 0, registers, registers);
  if (!s->ctx_ || !s->map_) throw Error("panel simulator: cannot create the libmodbus context");
  modbus_set_slave(s->ctx_, slave);
  s->listen_fd_ = modbus_tcp_listen(s->ctx_, 4);
  if (s->listen_fd_ < 0)
    throw Error("panel simulator: cannot listen on " + host + ":" + std::to_string(port) + ": " +
                modbus_strerror(errno));
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  getsockname(s->listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  s->port_ = ntohs(addr.sin_port);
  s->thread_ = std::thread([p = s.get()] { p->serve(p->stopping_); });
  return s;
}

std::unique_ptr<PanelSimulator> PanelSimulator::rtu(const std::string& device, int baud, char parity,
                                                    int registers, int slave) {
  std::unique_ptr<PanelSimulator> s(new PanelSimulator);
  s->rtu_ = true;
  s->ctx_ = modbus_new_rtu(device.c_str(), baud, parity, 8, 1);
  s->map_ = modbus_mapping_new(0, 0, registers, registers);
  if (!s->ctx_ || !s->map_)
    throw Error("panel simulator: cannot create the libmodbus RTU context for " + device);
  modbus_set_slave(s->ctx_, slave);
  if (modbus_connect(s->ctx_) < 0)
    throw Error("panel simulator: cannot open " + device + ": " + modbus_strerror(errno));
  s->thread_ = std::thread([p = s.get()] { p->serve(p->stopping_); });
  return s;
}

PanelSimulator::~PanelSimulator() {
  stop();
  if (map_) modbus_mapping_free(map_);
  if (ctx_) {
    modbus_close(ctx_);
    modbus_free(ctx_);
  }
}

void PanelSimulator::stop() {
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
  if (listen_fd_ >= 0) ::close(listen_fd_);
  listen_fd_ = -1;
}

void PanelSimulator::set_register(int address, std::uint16_t value) {
  std::lock_guard lock(mutex_);
  map_->tab_registers[address] = value;
  map_->tab_input_registers[address] = value;
}

std::uint16_t PanelSimulator::get_register(int address) const {
  std::lock_guard lock(mutex_);
  return map_->tab_registers[address];
}

void PanelSimulator::serve(const std::atomic<bool>& stop_flag) {
  if (rtu_)
    serve_rtu(stop_flag);
  else
    serve_tcp(stop_flag);
}

void PanelSimulator::handle(modbus_t* ctx) {
  std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
  const int n = modbus_receive(ctx, query);
  if (n <= 0) return;
  ++requests_;
  if (silent_) return;
  std::lock_guard lock(mutex_);
  modbus_reply(ctx, query, n, map_);
}

void PanelSimulator::serve_tcp(const std::atomic<bool>& stop_flag) {
  std::vector<int> clients;
  while (!stop_flag && !stopping_) {
    fd_set set;
    FD_ZERO(&set);
    FD_SET(listen_fd_, &set);
    int max_fd = listen_fd_;
    for (int c : clients) {
      FD_SET(c, &set);
      max_fd = std::max(max_fd, c);
    }
    if (!readable(max_fd, set, max_fd)) continue;
    if (FD_ISSET(listen_fd_, &set)) {
      const int c = accept(listen_fd_, nullptr, nullptr);
      if (c >= 0) clients.push_back(c);
    }
    for (auto it = clients.begin(); it != clients.end();) {
      if (!FD_ISSET(*it, &set)) {
        ++it;
        continue;
      }
      modbus_set_socket(ctx_, *it);
      std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
      const int n = modbus_receive(ctx_, query);
      if (n < 0) {  // the client went away
        ::close(*it);
        it = clients.erase(it);
        continue;
      }
      if (n > 0) {
        ++requests_;
        if (!silent_) {
          std::lock_guard lock(mutex_);
          modbus_reply(ctx_, query, n, map_);
        }
      }
      ++it;
    }
  }
  for (int c : clients) ::close(c);  // every connection drops at once, as when the process dies
  modbus_set_socket(ctx_, -1);
}

void PanelSimulator::serve_rtu(const std::atomic<bool>& stop_flag) {
  const int fd = modbus_get_socket(ctx_);
  while (!stop_flag && !stopping_) {
    fd_set set;
    FD_ZERO(&set);
    FD_SET(fd, &set);
    if (!readable(fd, set, fd)) continue;
    handle(ctx_);
  }
}

}  // namespace walk::devices
