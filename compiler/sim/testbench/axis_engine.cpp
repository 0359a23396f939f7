// The DMA streams of a replay, driven in C++ around the Verilated logic (rfc.sim.stream_engine).
//
// The processor side stays in Python, but only at transfer granularity: every beat, the idle
// cycles of the PS->PL source and the backpressure of the PL->PS sink are simulated here.
// The pause pattern (one byte per cycle, repeated) comes first on stdin; the sink follows the
// pattern backwards, as rfc's cocotb harness does.
//
// Interactive mode (default), little-endian binary on stdin/stdout:
//   'S' u32 n, n bytes   queue one PS->PL transfer
//   'R' u64 n, u8 stop   run at most n cycles, stopping after a cycle in which a transfer
//                        completed that `stop` names (1: PS->PL, 2: PL->PS); answers u64 cycles
//                        run, u8 flags (1: the PS->PL transfer completed, 4: a PL->PS transfer
//                        is under way), u64 the cycle it completed at (counted from 1 in this
//                        run), u32 k, then k completed PL->PS transfers as u64 cycle, u32 n,
//                        n bytes (those whose tkeep is set)
//   'P'                  answer u32 k and the k status registers as u64 (the top's busy
//                        port is the last when it has one)
//   'Q'                  answer as 'P', then exit
// Batch mode (--batch), the plain testbench without Python: 'S' as above, 'W' u64 n runs n
// cycles without stopping; every completed PL->PS transfer is written as u32 n, n bytes; at the
// end of the input the status registers follow as in 'Q'.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <memory>
#include <utility>
#include <vector>

#include "Vdut.h"
#include "engine_ports.h"  // RFC_LANES, RFC_STATUS_PORTS(X)
#include "verilated.h"

namespace {

constexpr int kLanes = RFC_LANES;

bool read_exact(void* into, size_t size) {
  return size == 0 || std::fread(into, 1, size, stdin) == size;
}

void write_exact(const void* from, size_t size) {
  if (size && std::fwrite(from, 1, size, stdout) != size) std::exit(3);
}

template <typename T>
T read_value() {
  T value{};
  if (!read_exact(&value, sizeof value)) std::exit(0);
  return value;
}

class Streams {
 public:
  explicit Streams(std::vector<uint8_t> pattern) : pattern_(std::move(pattern)) {
    dut_ = std::make_unique<Vdut>(&context_);
    dut_->aclk = 0;
    dut_->aresetn = 0;
    dut_->s_axis_mm2s_tvalid = 0;
    dut_->m_axis_s2mm_tready = 0;
    dut_->eval();
    for (int i = 0; i < 6; ++i) {  // four cycles in reset, two out of it, then the drivers
      dut_->aresetn = i >= 4;
      edge();
    }
  }

  void queue(std::vector<uint8_t> transfer) { queue_.push_back(std::move(transfer)); }

  bool receiving() const { return !received_.empty(); }

  // One cycle; returns the flags of what completed in it (1 sent, 2 received).
  int cycle() {
    int done = 0;
    bool sent = dut_->s_axis_mm2s_tvalid && dut_->s_axis_mm2s_tready;
    if (sent && dut_->s_axis_mm2s_tlast) done |= 1;
    if (dut_->m_axis_s2mm_tvalid && dut_->m_axis_s2mm_tready) {
      uint64_t data = dut_->m_axis_s2mm_tdata;
      uint64_t keep = dut_->m_axis_s2mm_tkeep;
      for (int lane = 0; lane < kLanes; ++lane) {
        if ((keep >> lane) & 1) received_.push_back(uint8_t(data >> (8 * lane)));
      }
      if (dut_->m_axis_s2mm_tlast) {
        completed_.swap(received_);
        received_.clear();
        done |= 2;
      }
    }
    edge_high();
    drive(sent);
    edge_low();
    ++count_;
    return done;
  }

  const std::vector<uint8_t>& completed() const { return completed_; }

  void report_status() {
    std::vector<uint64_t> values;
#define RFC_STATUS_VALUE(port) values.push_back(uint64_t(dut_->port));
    RFC_STATUS_PORTS(RFC_STATUS_VALUE)
#undef RFC_STATUS_VALUE
    uint32_t count = uint32_t(values.size());
    write_exact(&count, sizeof count);
    write_exact(values.data(), values.size() * sizeof(uint64_t));
    std::fflush(stdout);
  }

 private:
  void edge() {
    edge_high();
    edge_low();
  }
  void edge_high() {
    dut_->aclk = 1;
    dut_->eval();
  }
  void edge_low() {
    dut_->aclk = 0;
    dut_->eval();
  }

  // After the rising edge: the next beat of the source, the sink's ready.
  void drive(bool sent) {
    size_t at = count_ % pattern_.size();
    bool source_pause = pattern_[at] != 0;
    bool sink_pause = pattern_[pattern_.size() - 1 - at] != 0;
    dut_->m_axis_s2mm_tready = !sink_pause;
    if (dut_->s_axis_mm2s_tvalid && !sent) return;  // the beat on the bus waits
    if (!loaded_ && !queue_.empty()) {
      current_ = std::move(queue_.front());
      queue_.pop_front();
      offset_ = 0;
      loaded_ = true;
    }
    if (!loaded_ || source_pause) {
      dut_->s_axis_mm2s_tvalid = 0;
      dut_->s_axis_mm2s_tlast = 0;
      return;
    }
    uint64_t data = 0;
    uint64_t keep = 0;
    for (int lane = 0; lane < kLanes && offset_ < current_.size(); ++lane, ++offset_) {
      data |= uint64_t(current_[offset_]) << (8 * lane);
      keep |= uint64_t(1) << lane;
    }
    bool last = offset_ >= current_.size();
    dut_->s_axis_mm2s_tdata = data;
    dut_->s_axis_mm2s_tkeep = keep;
    dut_->s_axis_mm2s_tvalid = 1;
    dut_->s_axis_mm2s_tlast = last;
    if (last) loaded_ = false;
  }

  VerilatedContext context_;
  std::unique_ptr<Vdut> dut_;
  std::vector<uint8_t> pattern_;
  std::deque<std::vector<uint8_t>> queue_;
  std::vector<uint8_t> current_;
  size_t offset_ = 0;
  bool loaded_ = false;
  std::vector<uint8_t> received_;
  std::vector<uint8_t> completed_;
  uint64_t count_ = 0;
};

std::vector<uint8_t> read_transfer() {
  auto size = read_value<uint32_t>();
  std::vector<uint8_t> bytes(size);
  if (!read_exact(bytes.data(), size)) std::exit(2);
  return bytes;
}

void write_transfer(const std::vector<uint8_t>& bytes) {
  uint32_t size = uint32_t(bytes.size());
  write_exact(&size, sizeof size);
  write_exact(bytes.data(), bytes.size());
}

void interactive(Streams& streams) {
  std::vector<std::pair<uint64_t, std::vector<uint8_t>>> frames;
  for (;;) {
    char command = read_value<char>();
    if (command == 'S') {
      streams.queue(read_transfer());
    } else if (command == 'R') {
      auto most = read_value<uint64_t>();
      auto stop = read_value<uint8_t>();
      uint64_t ran = 0;
      uint64_t sent_at = 0;
      frames.clear();
      while (ran < most) {
        int done = streams.cycle();
        ++ran;
        if (done & 1) sent_at = ran;
        if (done & 2) frames.emplace_back(ran, streams.completed());
        if (done & stop) break;
      }
      uint8_t flags = uint8_t((sent_at ? 1 : 0) | (streams.receiving() ? 4 : 0));
      uint32_t count = uint32_t(frames.size());
      write_exact(&ran, sizeof ran);
      write_exact(&flags, sizeof flags);
      write_exact(&sent_at, sizeof sent_at);
      write_exact(&count, sizeof count);
      for (const auto& [at, bytes] : frames) {
        write_exact(&at, sizeof at);
        write_transfer(bytes);
      }
      std::fflush(stdout);
    } else if (command == 'P') {
      streams.report_status();
    } else if (command == 'Q') {
      streams.report_status();
      return;
    } else {
      std::exit(2);
    }
  }
}

void batch(Streams& streams) {
  char command;
  while (read_exact(&command, 1)) {
    if (command == 'S') {
      streams.queue(read_transfer());
    } else if (command == 'W') {
      auto cycles = read_value<uint64_t>();
      for (uint64_t i = 0; i < cycles; ++i) {
        if (streams.cycle() & 2) write_transfer(streams.completed());
      }
    } else {
      std::exit(2);
    }
  }
  streams.report_status();
}

}  // namespace

int main(int argc, char** argv) {
  bool batch_mode = argc > 1 && std::strcmp(argv[1], "--batch") == 0;
  auto length = read_value<uint32_t>();
  std::vector<uint8_t> pattern(length);
  if (length == 0 || !read_exact(pattern.data(), length)) return 2;
  Streams streams(std::move(pattern));
  if (batch_mode) {
    batch(streams);
  } else {
    interactive(streams);
  }
  return 0;
}
