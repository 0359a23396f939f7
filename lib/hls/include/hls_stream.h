// rfc's C-simulation stand-in for Vitis HLS's hls::stream: an unbounded FIFO.
//
// Enough of the vendor interface for accelerators C-simulated by `rfc sim` (read, write, empty,
// full, size, the non-blocking forms and the stream operators). Reading an empty stream is a
// bug of the accelerator that would hang the hardware, so the C simulation stops with a message
// naming the stream instead.
#ifndef RFC_HLS_STREAM_H
#define RFC_HLS_STREAM_H

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <string>

namespace hls {

template <typename T>
class stream {
  public:
    stream() : name_("stream") {}
    explicit stream(const char *name) : name_(name) {}
    stream(const stream &) = delete;
    stream &operator=(const stream &) = delete;

    T read() {
        if (fifo_.empty()) {
            std::fprintf(stderr, "rfc C simulation: read from empty stream %s\n", name_.c_str());
            std::exit(3);
        }
        T value = fifo_.front();
        fifo_.pop_front();
        return value;
    }
    void read(T &value) { value = read(); }
    bool read_nb(T &value) {
        if (fifo_.empty()) return false;
        value = read();
        return true;
    }
    void write(const T &value) { fifo_.push_back(value); }
    bool write_nb(const T &value) {
        write(value);
        return true;
    }
    stream &operator>>(T &value) {
        read(value);
        return *this;
    }
    stream &operator<<(const T &value) {
        write(value);
        return *this;
    }
    bool empty() const { return fifo_.empty(); }
    bool full() const { return false; }
    std::size_t size() const { return fifo_.size(); }
    const char *name() const { return name_.c_str(); }

  private:
    std::string name_;
    std::deque<T> fifo_;
};

}  // namespace hls

#endif  // RFC_HLS_STREAM_H
