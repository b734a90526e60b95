#include "parser/job_scan.hpp"

#include "parser/line_reader.hpp"
#include "support/ascii.hpp"
#include "support/file_reader.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <future>
#include <memory>
#include <optional>
#include <string_view>
#include <system_error>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace twinpost {

namespace {

// The number an argument starts with ("2" -> 2, "12AB" -> 12), when it starts with a digit
// and fits an int.
std::optional<int> leading_number(const std::string& a) {
  int n = 0;
  if (a.empty() || !ascii::is_digit(a[0])) return std::nullopt;
  if (std::from_chars(a.data(), a.data() + a.size(), n).ec != std::errc{}) return std::nullopt;
  return n;
}

// The first argument after the major word: "HEAD / 2" -> "2", "CHANNEL,1" -> "1".
std::string first_arg(std::string_view rest) {
  std::size_t p = 0;
  while (p < rest.size() && (rest[p] == ' ' || rest[p] == '\t')) ++p;
  if (p < rest.size() && (rest[p] == '/' || rest[p] == ',')) ++p;
  while (p < rest.size() && (rest[p] == ' ' || rest[p] == '\t')) ++p;
  std::string a;
  while (p < rest.size() && ascii::is_alnum(rest[p])) a += ascii::upper(rest[p++]);
  return a;
}

void scan_line(std::string_view l, job_scan& s) {
  while (!l.empty() && (l.front() == ' ' || l.front() == '\t')) l.remove_prefix(1);
  // Most lines are motion (GOTO, coordinates): one look at the first letter settles them.
  if (l.empty()) return;
  char c = ascii::upper(l.front());
  if (c != 'S' && c != 'H' && c != 'C' && c != '$') return;
  if (ascii::starts_with_keyword(l, "SYNC")) s.explicit_sync = true;  // SYNC/ and SYNCTR/
  // A part transfer is no sync record: its waits are a barrier under every policy, and the
  // work between them is placed by `auto` as any other (issue 39, item 6).
  if (ascii::starts_with_keyword(l, "$$UDE") && l.find("SYNCHRONIZATION") != std::string_view::npos)
    s.explicit_sync = true;
  if (ascii::starts_with_keyword(l, "HEAD")) {
    std::string a = first_arg(l.substr(4));
    if (a == "BOTH") {
      s.heads.push_back(1);
      s.heads.push_back(2);
    } else if (const std::optional<int> h = leading_number(a)) {
      s.heads.push_back(*h);
    } else if (!a.empty() && !ascii::is_digit(a[0])) {
      s.head_words.push_back(a);
    }
  }
  std::size_t n = ascii::starts_with_keyword(l, "CHANNEL")  ? 7
                  : ascii::starts_with_keyword(l, "CHANNL") ? 6
                                                            : 0;
  if (n > 0) {
    std::string a = first_arg(l.substr(n));
    if (const std::optional<int> ch = leading_number(a)) s.channels.push_back(*ch);
  }
}

// The first of S, H, C (either case) or $ in [p, end), or end. Motion records have none of
// them: sixteen bytes are tested at once (a byte with 0x20 set is s, h, c or $ only if it
// was one of the seven).
const char* next_candidate(const char* p, const char* end) {
#if defined(__SSE2__)
  const __m128i lower = _mm_set1_epi8(0x20);
  const __m128i s = _mm_set1_epi8('s'), h = _mm_set1_epi8('h'), c = _mm_set1_epi8('c'),
                dollar = _mm_set1_epi8('$');
  for (; end - p >= 16; p += 16) {
    const __m128i v = _mm_or_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), lower);
    const __m128i any = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(v, s), _mm_cmpeq_epi8(v, h)),
                                     _mm_or_si128(_mm_cmpeq_epi8(v, c), _mm_cmpeq_epi8(v, dollar)));
    if (const int mask = _mm_movemask_epi8(any)) return p + std::countr_zero(static_cast<unsigned>(mask));
  }
#endif
  for (; p < end; ++p) {
    const char u = static_cast<char>(*p | 0x20);
    if (u == 's' || u == 'h' || u == 'c' || u == '$') return p;
  }
  return end;
}

// The lines of `text` (the last one may have no line end). Only lines that start, after
// blanks, with S, H, C or $ can matter, and motion records have none of those letters at all.
void scan_lines(std::string_view text, job_scan& s) {
  const char* const begin = text.data();
  const char* const end = begin + text.size();
  const char* p = begin;
  while (p < end) {
    const char* hit = next_candidate(p, end);
    if (hit >= end) return;
    // The line the hit is on; it counts only if nothing but blanks comes before it. TRANSFER
    // (a part transfer, a synchronisation of its own) is found by its S.
    const char* line = hit;
    if (hit - begin >= 4 && (*hit == 'S' || *hit == 's') && ascii::upper(hit[-4]) == 'T' &&
        ascii::upper(hit[-3]) == 'R' && ascii::upper(hit[-2]) == 'A' && ascii::upper(hit[-1]) == 'N')
      line = hit - 4;
    while (line > begin && (line[-1] == ' ' || line[-1] == '\t')) --line;
    const char* eol = static_cast<const char*>(std::memchr(hit, '\n', static_cast<std::size_t>(end - hit)));
    if (!eol) eol = end;
    if (line == begin || line[-1] == '\n' || line[-1] == '\r')
      scan_line(std::string_view(line, static_cast<std::size_t>(eol - line)), s);
    p = eol + 1;
  }
}

// A regular file's bytes mapped for reading (no copy into a buffer of ours); empty when the
// file is not one (a pipe) or cannot be mapped.
class mapped_file {
 public:
  mapped_file(int fd, std::size_t size) {
    void* at = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (at == MAP_FAILED) return;
    data_ = static_cast<const char*>(at);
    size_ = size;
  }
  ~mapped_file() {
    if (data_) ::munmap(const_cast<char*>(data_), size_);
  }
  mapped_file(const mapped_file&) = delete;
  mapped_file& operator=(const mapped_file&) = delete;
  std::string_view text() const { return {data_, size_}; }
  explicit operator bool() const { return data_ != nullptr; }
  /// Makes the pages of [from, to) present at once: one call instead of a fault per few
  /// pages (a kernel without MADV_POPULATE_READ refuses it, and the faults come as before).
  void populate(std::size_t from, std::size_t to) const {
#if defined(MADV_POPULATE_READ)
    const std::size_t start = from / page() * page();
    ::madvise(const_cast<char*>(data_) + start, to - start, MADV_POPULATE_READ);
#else
    (void)from, (void)to;
#endif
  }
  /// The pages wholly inside [from, to) are not needed again: out of the process's memory
  /// (the file's pages stay in the page cache).
  void release(std::size_t from, std::size_t to) const {
    const std::size_t start = (from + page() - 1) / page() * page(), end = to / page() * page();
    if (end > start) ::madvise(const_cast<char*>(data_) + start, end - start, MADV_DONTNEED);
  }

 private:
  static std::size_t page() {
    static const auto size = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    return size;
  }
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

// The whole lines of `text` in [from, to), each window let go once read: a job of gigabytes
// costs the scan no more memory than a small one. The first window is 256 KB and each next
// twice the last, up to 8 MB: a scan that stops early maps little, a long one makes few calls.
// After each window `go_on(end)` says whether to read on; false when it stopped the scan.
// `from` and `to` are line starts (or the text's end).
template <class GoOn>
bool scan_range(const mapped_file& mapped, std::size_t from, std::size_t to, job_scan& s, GoOn&& go_on) {
  constexpr std::size_t first_window = std::size_t{256} << 10, last_window = std::size_t{8} << 20;
  const std::string_view text = mapped.text();
  std::size_t window = first_window;
  for (std::size_t done = from; done < to;) {
    std::size_t end = std::min(to, done + window);
    if (end < to) {
      const std::size_t nl = text.find('\n', end);
      end = nl == std::string_view::npos || nl >= to ? to : nl + 1;
    }
    mapped.populate(done, end);
    scan_lines(text.substr(done, end - done), s);
    mapped.release(done, end);
    done = end;
    window = std::min(window * 2, last_window);
    if (!go_on(end)) return false;
  }
  return true;
}

// What a later part of the job found, after what an earlier part found.
void append_scan(job_scan& to, job_scan&& later) {
  to.explicit_sync = to.explicit_sync || later.explicit_sync;
  to.heads.insert(to.heads.end(), later.heads.begin(), later.heads.end());
  for (std::string& w : later.head_words) to.head_words.push_back(std::move(w));
  to.channels.insert(to.channels.end(), later.channels.begin(), later.channels.end());
}

// From this size on a mapped job is scanned in two halves at once: the scan is the serial start
// of a multi-channel post, and the second core has little else to do then.
constexpr std::size_t split_bytes = std::size_t{4} << 20;

}  // namespace

job_scan scan_job(const std::string& path, const std::function<bool(const job_scan&)>& enough) {
  job_scan s;
  // Opened once: a pipe's bytes can be read only once.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return s;
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    if (st.st_size == 0) {
      ::close(fd);
      return s;
    }
    const mapped_file mapped(fd, static_cast<std::size_t>(st.st_size));
    if (mapped) {
      ::close(fd);
      const std::string_view text = mapped.text();
      std::size_t half = text.size();
      if (text.size() >= split_bytes) {
        const std::size_t nl = text.find('\n', text.size() / 2);
        half = nl == std::string_view::npos ? text.size() : nl + 1;
      }
      // The first half here, asking `enough` after each window. The second half on a thread of
      // its own, started after the first window (a job whose answer is in its first lines
      // costs no thread); where none can start, this one scans it after the first. When
      // `enough` stops the first half, the second stops at its next window and what it found
      // is dropped: the result is the first part's, wherever the thread had got to.
      // `stop` and `later` before `second`, and `stopper` after it: should this thread throw,
      // `stop` is set first, and the future then waits for the scan's thread (one window at
      // most) while both still exist.
      std::atomic<bool> stop{false};
      job_scan later;
      std::future<void> second;
      struct stopper {
        std::atomic<bool>& stop;
        ~stopper() { stop = true; }
      } stop_on_exit{stop};
      bool tried = half == text.size();  // no second half, or its thread was asked for
      const bool whole = scan_range(mapped, 0, half, s, [&](std::size_t) {
        if (enough && enough(s)) return false;
        if (!tried) {
          tried = true;
          try {
            second = std::async(std::launch::async, [&] {
              scan_range(mapped, half, text.size(), later,
                         [&stop](std::size_t) { return !stop.load(std::memory_order_relaxed); });
            });
          } catch (const std::system_error&) {
          }
        }
        return true;
      });
      if (!whole) {
        stop = true;
        if (second.valid()) second.wait();  // its findings, or its failure, are not needed
        return s;
      }
      if (second.valid())
        second.get();
      else if (half < text.size())
        scan_range(mapped, half, text.size(), later, [](std::size_t) { return true; });
      append_scan(s, std::move(later));
      return s;
    }
  }
  const file_ptr f(::fdopen(fd, "rb"), &std::fclose);
  if (!f) {
    ::close(fd);
    return s;
  }
  chunk_reader reader(f.get());
  std::string carry;  // a line begun in the previous chunk
  // Only a line's first words matter, and the reader refuses lines past max_record_bytes:
  // a line without a newline must not grow the carry without bound.
  auto keep = [&carry](std::string_view part) {
    if (carry.size() < max_record_bytes) carry.append(part.substr(0, max_record_bytes - carry.size()));
  };
  for (std::string_view chunk; !(chunk = reader.next()).empty();) {
    std::size_t start = 0;
    if (!carry.empty()) {
      const void* nl = std::memchr(chunk.data(), '\n', chunk.size());
      if (!nl) {
        keep(chunk);
        continue;
      }
      std::size_t end = static_cast<std::size_t>(static_cast<const char*>(nl) - chunk.data());
      keep(chunk.substr(0, end));
      scan_line(carry, s);
      carry.clear();
      start = end + 1;
    }
    // Whole lines here; what follows the last '\n' waits for the next chunk.
    std::size_t last = chunk.rfind('\n');
    if (last == std::string_view::npos || last < start) {
      keep(chunk.substr(start));
      continue;
    }
    scan_lines(chunk.substr(start, last + 1 - start), s);
    keep(chunk.substr(last + 1));
  }
  scan_line(carry, s);
  return s;
}

}  // namespace twinpost
