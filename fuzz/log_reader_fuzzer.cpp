/// @file
/// libFuzzer target: arbitrary bytes as an LCM log file, read by the log
/// reader every command uses (logs/log_event_reader.hpp) -- what `lagrange
/// replay`, `report` and `view` do with a log before anything decodes a
/// message. A crash, a sanitizer report (ASan, UBSan), an exception other
/// than LogError escaping, or bytes unaccounted for is a finding: every byte
/// of the file must be read as an event, skipped as corrupt or as an event
/// over its channel's bound, or counted as the unreadable end.
///
/// Run: bash scripts/fuzz.sh [SECONDS]   (corpus: fuzz/corpus/logs)

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "logs/log_event_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;  // fmemopen refuses an empty buffer; the empty log is a unit test
  std::FILE* file = fmemopen(const_cast<uint8_t*>(data), size, "rb");
  if (file == nullptr) return 0;
  const auto total = static_cast<long long>(size);
  try {
    lagrange::logs::LogEventReader reader(file, total, "fuzz.lcm");
    long long event_bytes = 0;
    unsigned sum = 0;
    while (const lcm::LogEvent* ev = reader.next()) {
      if (ev->datalen < 0 || ev->datalen > total || ev->channel.empty()) std::abort();
      // Every byte handed out is read: ASan reports a short buffer.
      for (int32_t i = 0; i < ev->datalen; ++i) sum += static_cast<const unsigned char*>(ev->data)[i];
      event_bytes +=
          lagrange::logs::log_format::kHeaderBytes + static_cast<long long>(ev->channel.size()) + ev->datalen;
    }
    const lagrange::logs::LogScan& scan = reader.scan();
    if (event_bytes + scan.skipped_bytes + scan.oversized_bytes + scan.unreadable_tail_bytes != total)
      std::abort();
    if ((scan.oversized_events > 0) != !scan.first_oversized.empty()) std::abort();
    if ((scan.skipped_bytes > 0) != (scan.first_skipped_at >= 0)) std::abort();
    (void)scan.problems();
    (void)sum;
  } catch (const lagrange::logs::LogError&) {
    // A malformed log, named: what the commands report with exit 2.
  }
  std::fclose(file);
  return 0;
}
