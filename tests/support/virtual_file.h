// fluid tests — a large file that is never written: `head` followed by `bodySize` zero bytes,
// served by a seekable std::streambuf that counts the bytes it hands out. A loader's test reads
// how much of a huge file it read before refusing it, without making the file.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <ios>
#include <streambuf>
#include <string>
#include <vector>

namespace fluid::test {

/// `head` then `bodySize` zeros (unit: bytes), read through a 64 KiB window.
/// Thread rule: one thread.
class VirtualFile : public std::streambuf {
public:
    /// A file of `head.size() + bodySize` bytes.
    VirtualFile(std::string head, uint64_t bodySize)
        : m_head(std::move(head)), m_size(m_head.size() + bodySize), m_window(kWindow) {}
    /// Bytes handed out so far (unit: bytes; a window counts whole once filled).
    uint64_t served() const { return m_served; }

protected:
    int_type underflow() override {
        if (m_at >= m_size) {
            return traits_type::eof();
        }
        const uint64_t n = std::min<uint64_t>(kWindow, m_size - m_at);
        std::fill(m_window.begin(), m_window.end(), '\0');
        if (m_at < m_head.size()) {
            const uint64_t fromHead = std::min<uint64_t>(n, m_head.size() - m_at);
            std::memcpy(m_window.data(), m_head.data() + m_at, fromHead);
        }
        setg(m_window.data(), m_window.data(), m_window.data() + n);
        m_start = m_at;
        m_at += n;
        m_served += n;
        return traits_type::to_int_type(m_window[0]);
    }
    pos_type seekoff(off_type off, std::ios_base::seekdir dir,
                     std::ios_base::openmode /*which*/) override {
        const uint64_t here = m_start + uint64_t(gptr() - eback());
        const uint64_t base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? here
                                                                                         : m_size;
        return seekpos(pos_type(off_type(base) + off), std::ios_base::in);
    }
    pos_type seekpos(pos_type pos, std::ios_base::openmode /*which*/) override {
        if (pos < 0 || uint64_t(pos) > m_size) {
            return pos_type(off_type(-1));
        }
        m_at = uint64_t(pos);
        m_start = m_at;
        setg(m_window.data(), m_window.data(), m_window.data()); // empty: refilled on read
        return pos;
    }

private:
    static constexpr uint64_t kWindow = 65536;
    std::string m_head;
    uint64_t m_size = 0;
    uint64_t m_at = 0;    // the stream position after the window
    uint64_t m_start = 0; // the stream position of the window's first byte
    uint64_t m_served = 0;
    std::vector<char> m_window;
};

} // namespace fluid::test
