// Verilator C++ harness of the accelerator: drives msr_sim_top (msr_top + DPI rendering unit)
// as a driver and a memory system would, for one frame.
//
//   Vmsr_sim_top --width W --height H [--tile T] [--levels L] [--thr a,b,c] [--metric max|sum]
//       [--fov-gain G] [--gaze X,Y] [--rule patent|lindilate|N] [--frame OUT.ppm] [--source OUT.pgm] [--stats OUT.json]
//       [--depth OUT.pgm] (a DEPTH_EN build: every pixel's inverse depth as it left its engine, 16-bit PGM;
//       +invz_exp=E sets the rendering unit's exponent)
//       [--budget PIXELS] [--scale-init U] [--prior-shift P] [--seeded 0|1]   (docs/budget.md)
//       [--frames N [--cameras FILE] [--gazes FILE]]   (a sequence: N frames in this one run,
//       the registers reprogrammed between frames as a driver would; FILE has one camera line per
//       frame, resp. one gaze line per frame, X,Y or - for --gaze's (a path's gaze points); with
//       a budget each frame after the first is seeded with the last SCALE_OUT; --frame and
//       --source are then printf patterns of the frame number, --stats gets one line per frame)
//       [--timeout CYCLES] [--mem-pause PERCENT] [--seed N] [--quiet]
//       [--fb-base ADDR]   (override FB_BASE; memory stays where it is: error-path tests)
//       (--rule N: CONFIG.RULE written as is, 0..3; 2 and 3 are refused by the hardware, ERROR 13)
//       (--gaze X,Y: GAZE written with EN, X and Y cut to their fields; a point outside the frame
//       is refused by the hardware, ERROR 16; without it GAZE is 0: the frame centre)
//       [--waves FILE.fst --wave-tile TX,TY | --wave-cycles FROM,TO]   (waves build only)
//       +scene=NAME|FILE +width=W +height=H [+rnd_latency=N] [+rnd_jitter=J]   (render_dpi)
//       [+camera=EX,EY,EZ,TX,TY,TZ,FOV]   (the view, read by msr_dpi.cpp)
//
// Exit status: 0 frame done, 1 failure (timeout, error status, write error), 2 bad arguments.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "Vmsr_sim_top.h"
#include "Vmsr_sim_top___024root.h"  // the build's parameters (verilator --public-params, mk/sim.mk)
#include "msr_dpi.h"
#include "msr_regs.h"
#include "verilated.h"

// Frame-buffer AXI data width of msr_sim_top (msr_top's default AXI_DATA_W = 256 bits).
constexpr unsigned kBeatBytes = 32;
static_assert(sizeof(Vmsr_sim_top::m_axi_wdata) == kBeatBytes, "harness expects a 256-bit W channel");
#if VM_TRACE
#include "verilated_fst_c.h"
#endif

namespace {

constexpr int kExitOk = 0, kExitFail = 1, kExitUsage = 2;

// Register byte offsets from the generated register struct, as a driver computes them.
#define REG(name) static_cast<uint32_t>(offsetof(msr_regs_t, name))

struct Options {
  int width = 320, height = 240, tile = 16, levels = 2, metric = 0, fov_gain = 0;
  int rule = 0;  // CONFIG.RULE: 0 patent, 1 lindilate (docs/rules.md)
  long gaze_x = -1, gaze_y = -1;  // GAZE.X, GAZE.Y with GAZE.EN; -1: not given (GAZE 0)
  // Ray budget (docs/budget.md): BUDGET.PIXELS (0 = off) and BUDGET_CTRL, written as given.
  long budget = 0, scale_init = 256, prior_shift = 6, seeded = 0;
  long frames = 1;                  // a sequence of frames in one run
  std::vector<std::string> cameras; // --cameras: the view of each frame
  std::vector<std::pair<long, long>> gazes;  // --gazes: each frame's gaze, {-1, -1}: --gaze's
  int thr[3] = {8, 16, 32};
  std::string frame_out, source_out, stats_out, waves;
  std::string depth_out;  // --depth: the engines' inverse-depth plane (a DEPTH_EN build), 16-bit PGM
  uint64_t timeout = 0;  // 0: derived from the frame size
  int mem_pause = 0;     // percent of cycles each AXI channel is not ready
  unsigned seed = 1;
  long long fb_base = -1;  // -1: the harness's own layout
  bool quiet = false;
  int wave_tx = -1, wave_ty = -1;
  uint64_t wave_from = 0, wave_to = 0;
};

[[noreturn]] void usage(const std::string &msg) {
  std::fprintf(stderr, "harness: error: %s\n", msg.c_str());
  std::exit(kExitUsage);
}

long to_int(const char *s, const char *what) {
  char *end = nullptr;
  long v = std::strtol(s, &end, 0);
  if (end == s || *end != '\0') usage(std::string(what) + " needs an integer, got '" + s + "'");
  return v;
}

Options parse(int argc, char **argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a[0] == '+') continue;  // plusargs belong to the simulation
    auto next = [&](const char *what) -> const char * {
      if (i + 1 >= argc) usage(std::string(what) + " needs a value");
      return argv[++i];
    };
    if (a == "--width") o.width = to_int(next("--width"), "--width");
    else if (a == "--height") o.height = to_int(next("--height"), "--height");
    else if (a == "--tile") o.tile = to_int(next("--tile"), "--tile");
    else if (a == "--levels") o.levels = to_int(next("--levels"), "--levels");
    else if (a == "--fov-gain") o.fov_gain = to_int(next("--fov-gain"), "--fov-gain");
    else if (a == "--timeout") o.timeout = to_int(next("--timeout"), "--timeout");
    else if (a == "--mem-pause") o.mem_pause = to_int(next("--mem-pause"), "--mem-pause");
    else if (a == "--seed") o.seed = to_int(next("--seed"), "--seed");
    else if (a == "--fb-base") o.fb_base = to_int(next("--fb-base"), "--fb-base");
    else if (a == "--frame") o.frame_out = next("--frame");
    else if (a == "--source") o.source_out = next("--source");
    else if (a == "--depth") o.depth_out = next("--depth");
    else if (a == "--stats") o.stats_out = next("--stats");
    else if (a == "--waves") o.waves = next("--waves");
    else if (a == "--quiet") o.quiet = true;
    else if (a == "--metric") {
      std::string m = next("--metric");
      if (m != "max" && m != "sum") usage("--metric must be max or sum");
      o.metric = (m == "sum");
    } else if (a == "--rule") {
      std::string r = next("--rule");
      if (r == "patent") o.rule = 0;
      else if (r == "lindilate") o.rule = 1;
      else if (r.size() == 1 && r[0] >= '0' && r[0] <= '3') o.rule = r[0] - '0';
      else usage("--rule must be patent, lindilate or a CONFIG.RULE value 0..3, got '" + r + "'");
    } else if (a == "--budget") {
      o.budget = to_int(next("--budget"), "--budget");
    } else if (a == "--scale-init") {
      o.scale_init = to_int(next("--scale-init"), "--scale-init");
    } else if (a == "--prior-shift") {
      o.prior_shift = to_int(next("--prior-shift"), "--prior-shift");
    } else if (a == "--seeded") {
      o.seeded = to_int(next("--seeded"), "--seeded");
    } else if (a == "--frames") {
      o.frames = to_int(next("--frames"), "--frames");
      if (o.frames < 1 || o.frames > 100000) usage("--frames must be 1..100000");
    } else if (a == "--cameras") {
      const char *f = next("--cameras");
      std::ifstream in(f);
      if (!in) usage(std::string("cannot read --cameras ") + f);
      for (std::string line; std::getline(in, line);)
        if (!line.empty()) o.cameras.push_back(line);
    } else if (a == "--gazes") {
      const char *f = next("--gazes");
      std::ifstream in(f);
      if (!in) usage(std::string("cannot read --gazes ") + f);
      for (std::string line; std::getline(in, line);) {
        if (line.empty()) continue;
        long x = -1, y = -1;
        char tail = 0;
        if (line != "-" && (std::sscanf(line.c_str(), "%ld,%ld%c", &x, &y, &tail) != 2 || x < 0 || y < 0))
          usage("--gazes: line " + std::to_string(o.gazes.size() + 1) + " is not X,Y (integers >= 0) or -");
        o.gazes.emplace_back(x, y);
      }
    } else if (a == "--thr") {
      std::string s = next("--thr");
      int k = 0;
      size_t pos = 0;
      while (pos <= s.size() && k < 3) {
        size_t c = s.find(',', pos);
        std::string part = s.substr(pos, c == std::string::npos ? std::string::npos : c - pos);
        o.thr[k++] = to_int(part.c_str(), "--thr");
        if (c == std::string::npos) break;
        pos = c + 1;
      }
    } else if (a == "--gaze") {
      char tail = 0;
      if (std::sscanf(next("--gaze"), "%ld,%ld%c", &o.gaze_x, &o.gaze_y, &tail) != 2 || o.gaze_x < 0 ||
          o.gaze_y < 0)
        usage("--gaze needs X,Y (two integers >= 0)");
    } else if (a == "--wave-tile") {
      if (std::sscanf(next("--wave-tile"), "%d,%d", &o.wave_tx, &o.wave_ty) != 2)
        usage("--wave-tile needs TX,TY");
    } else if (a == "--wave-cycles") {
      unsigned long long f, t;
      if (std::sscanf(next("--wave-cycles"), "%llu,%llu", &f, &t) != 2 || t < f)
        usage("--wave-cycles needs FROM,TO");
      o.wave_from = f;
      o.wave_to = t;
    } else {
      usage("unknown option " + a);
    }
  }
  if (!o.gazes.empty() && static_cast<long>(o.gazes.size()) != o.frames)
    usage("--gazes has " + std::to_string(o.gazes.size()) + " lines for " + std::to_string(o.frames) +
          " frames");
  if (!o.cameras.empty() && static_cast<long>(o.cameras.size()) != o.frames)
    usage("--cameras has " + std::to_string(o.cameras.size()) + " lines for " + std::to_string(o.frames) +
          " frames");
  // Register values are NOT checked here: the hardware checks them (STATUS.ERROR).
  return o;
}

// The simulated system: model + clock + the two bus agents.
class Sim {
 public:
  Sim(VerilatedContext *ctx, const Options &o) : ctx_(ctx), o_(o), rng_(o.seed) {
    top_ = std::make_unique<Vmsr_sim_top>(ctx_, "TOP");
    half_ = half_period_steps(ctx_);  // the model has set the context's time precision
    fb_stride_ = 4u * static_cast<uint32_t>(o.width);
    src_stride_ = (static_cast<uint32_t>(o.width) + 3u) & ~3u;
    fb_base_ = 0x1000;  // not 0, so a base bug shows
    src_base_ = (fb_base_ + fb_stride_ * o.height + 0xFFFu) & ~0xFFFu;
    mem_.assign(src_base_ + src_stride_ * o.height, 0xEE);
  }
  ~Sim() {
#if VM_TRACE
    if (tfp_) tfp_->close();
#endif
    top_->final();
  }

  void open_waves() {
#if VM_TRACE
    if (o_.waves.empty()) return;
    ctx_->traceEverOn(true);
    tfp_ = std::make_unique<VerilatedFstC>();
    top_->trace(tfp_.get(), 99);
    tfp_->open(o_.waves.c_str());
#else
    if (!o_.waves.empty()) usage("--waves needs the harness built with tracing (make sim WAVES=1)");
#endif
  }

  // Simulated time: the SDC's 100 MHz clock, a 10 ns period, so a waveform viewer reads real
  // times. Half a period in the model's time precision (Verilator's default 1 ps: 5000 steps).
  static uint64_t half_period_steps(const VerilatedContext *ctx) {
    uint64_t steps = 5;  // 5 ns = 5 * 10^(-9 - precision) steps of 10^precision s
    for (int p = ctx->timeprecision(); p < -9; ++p) steps *= 10;
    return steps;
  }

  // One clock cycle: inputs settle at the falling edge, agents sample after the rising edge.
  void tick() {
    top_->clk_i = 0;
    top_->eval();
    dump();
    ctx_->timeInc(half_);
    top_->clk_i = 1;
    top_->eval();
    // Everything visible now is what the rising edge produced; agents react for the next one.
    mem_agent();
    lite_agent();
    top_->eval();
    dump();
    ctx_->timeInc(half_);
    ++cycle_;
    tile_window();
  }

  void reset() {
    // The tile the FST window follows (if any); the top reports when its last pixel leaves.
    top_->dbg_watch_tx_i = o_.wave_tx >= 0 ? o_.wave_tx : 0xFFF;
    top_->dbg_watch_ty_i = o_.wave_ty >= 0 ? o_.wave_ty : 0xFFF;
    top_->dbg_watch_t_i = o_.tile;
    top_->rst_ni = 0;
    for (int i = 0; i < 4; ++i) tick();
    top_->rst_ni = 1;
    tick();
  }

  // AXI4-Lite, as a driver does it: one transaction at a time, wait for the response.
  void write_reg(uint32_t addr, uint32_t data) {
    lite_.op = Lite::kWrite;
    lite_.addr = addr;
    lite_.data = data;
    lite_.aw_done = lite_.w_done = false;
    lite_run();
  }
  uint32_t read_reg(uint32_t addr) {
    lite_.op = Lite::kRead;
    lite_.addr = addr;
    lite_run();
    return lite_.data;
  }

  uint64_t cycle() const { return cycle_; }
  uint64_t pixels_written() const { return pixels_written_; }
  bool write_error() const { return write_error_; }
  uint32_t pixel(int x, int y) const {
    uint32_t a = fb_base_ + y * fb_stride_ + 4 * x, v;
    std::memcpy(&v, &mem_[a], 4);
    return v;
  }
  uint8_t code(int x, int y) const { return mem_[src_base_ + y * src_stride_ + x]; }
  uint32_t fb_base() const { return fb_base_; }
  uint32_t fb_stride() const { return fb_stride_; }
  uint32_t src_base() const { return src_base_; }
  uint32_t src_stride() const { return src_stride_; }

 private:
  struct Lite {
    enum Op { kIdle, kWrite, kRead } op = kIdle;
    uint32_t addr = 0, data = 0;
    bool aw_done = false, w_done = false, ar_done = false;
    bool finished = false;
  } lite_;

  struct Burst {
    uint32_t addr;
    unsigned beats;
  };

  void lite_run() {
    lite_.finished = false;
    lite_.ar_done = false;
    for (int guard = 0; !lite_.finished; ++guard) {
      if (guard > 1000) {
        std::fprintf(stderr, "harness: error: register access 0x%02x hangs\n", lite_.addr);
        std::exit(kExitFail);
      }
      lite_drive();
      tick();
    }
    lite_.op = Lite::kIdle;
    lite_drive();
  }

  // Outputs of the driver for the next rising edge.
  void lite_drive() {
    top_->s_axil_awvalid = lite_.op == Lite::kWrite && !lite_.aw_done;
    top_->s_axil_wvalid = lite_.op == Lite::kWrite && !lite_.w_done;
    top_->s_axil_awaddr = lite_.addr;
    top_->s_axil_wdata = lite_.data;
    top_->s_axil_bready = lite_.op == Lite::kWrite;
    top_->s_axil_arvalid = lite_.op == Lite::kRead && !lite_.ar_done;
    top_->s_axil_araddr = lite_.addr;
    top_->s_axil_rready = lite_.op == Lite::kRead;
  }

  // Sample the handshakes of the rising edge that just happened (values before the edge are
  // what counted; the model's outputs after the edge are the new ones). To keep it simple the
  // agent compares with what it drove and what the model showed before the edge.
  void lite_agent() {
    if (lite_.op == Lite::kIdle) return;
    if (lite_.op == Lite::kWrite) {
      if (!lite_.aw_done && pre_.awready) lite_.aw_done = true;
      if (!lite_.w_done && pre_.wready) lite_.w_done = true;
      if (pre_.bvalid) {
        if (pre_.bresp != 0) {
          std::fprintf(stderr, "harness: error: register write 0x%02x answered %u\n", lite_.addr, pre_.bresp);
          std::exit(kExitFail);
        }
        lite_.finished = true;
      }
    } else {
      if (!lite_.ar_done && pre_.arready) lite_.ar_done = true;
      if (pre_.rvalid) {
        lite_.data = pre_.rdata;
        lite_.finished = true;
      }
    }
  }

  // AXI4 slave memory: AW into a queue, W beats written with strobes, one B per burst.
  void mem_agent() {
    // Handshakes of the edge that just happened (inputs we drove, outputs from before the edge).
    if (pre_.awvalid && mem_awready_) aw_q_.push_back({pre_.awaddr, pre_.awlen + 1u});
    if (pre_.wvalid && mem_wready_) {
      if (aw_q_.empty()) {
        std::fprintf(stderr, "harness: error: W beat without an address\n");
        std::exit(kExitFail);
      }
      const Burst &b = aw_q_.front();
      // One beat = kBeatBytes bytes at the burst's bus-aligned address; strobed bytes only.
      const uint64_t a = static_cast<uint64_t>(b.addr) + kBeatBytes * w_beat_;
      bool ok = true;
      for (unsigned k = 0; k < kBeatBytes; ++k) {
        if (!(pre_.wstrb & (1u << k))) continue;
        if (a + k >= mem_.size()) {
          ok = false;
          continue;
        }
        mem_[a + k] = static_cast<uint8_t>(pre_.wdata[k / 4] >> (8 * (k % 4)));
      }
      for (unsigned lane = 0; lane < kBeatBytes / 4; ++lane) {
        const uint64_t la = a + 4 * lane;
        if (ok && la >= fb_base_ && la < src_base_ && ((pre_.wstrb >> (4 * lane)) & 0xFu) == 0xFu)
          ++pixels_written_;
      }
      burst_err_ |= !ok;
      ++w_beat_;
      const bool last_expected = (w_beat_ == b.beats);
      if (pre_.wlast != last_expected) {
        std::fprintf(stderr, "harness: error: WLAST %d at beat %u of %u\n", pre_.wlast, w_beat_, b.beats);
        std::exit(kExitFail);
      }
      if (pre_.wlast) {
        b_q_.push_back(burst_err_ ? 2 : 0);  // SLVERR outside the memory
        burst_err_ = false;
        w_beat_ = 0;
        aw_q_.pop_front();
      }
    }
    if (pre_.bvalid_out && pre_.bready) {
      b_q_.pop_front();
    }
    // Drive for the next edge.
    std::uniform_int_distribution<int> pct(0, 99);
    mem_awready_ = pct(rng_) >= o_.mem_pause;
    mem_wready_ = pct(rng_) >= o_.mem_pause;
    const bool b_ok = pct(rng_) >= o_.mem_pause;
    top_->m_axi_awready = mem_awready_;
    top_->m_axi_wready = mem_wready_;
    top_->m_axi_bvalid = !b_q_.empty() && (b_ok || bvalid_);
    bvalid_ = top_->m_axi_bvalid;
    top_->m_axi_bresp = b_q_.empty() ? 0 : b_q_.front();
    if (!b_q_.empty() && b_q_.front() != 0 && top_->m_axi_bvalid) write_error_ = true;
  }

  // What the model showed before a rising edge: sampled at the end of tick's low phase.
  struct Pre {
    bool awready, wready, bvalid, arready, rvalid;
    unsigned bresp;
    uint32_t rdata;
    bool awvalid, wvalid, wlast, bready, bvalid_out;
    uint32_t awaddr, wdata[kBeatBytes / 4];
    unsigned awlen, wstrb;
  } pre_{};

  void sample_pre() {
    pre_.awready = top_->s_axil_awready;
    pre_.wready = top_->s_axil_wready;
    pre_.bvalid = top_->s_axil_bvalid && top_->s_axil_bready;
    pre_.bresp = top_->s_axil_bresp;
    pre_.arready = top_->s_axil_arready;
    pre_.rvalid = top_->s_axil_rvalid && top_->s_axil_rready;
    pre_.rdata = top_->s_axil_rdata;
    pre_.awvalid = top_->m_axi_awvalid;
    pre_.awaddr = top_->m_axi_awaddr;
    pre_.awlen = top_->m_axi_awlen;
    pre_.wvalid = top_->m_axi_wvalid;
    for (unsigned i = 0; i < kBeatBytes / 4; ++i) pre_.wdata[i] = top_->m_axi_wdata[i];
    pre_.wstrb = top_->m_axi_wstrb;
    pre_.wlast = top_->m_axi_wlast;
    pre_.bready = top_->m_axi_bready;
    pre_.bvalid_out = top_->m_axi_bvalid;
    dbg_fire_ = top_->dbg_desc_fire_o;
    dbg_x0_ = top_->dbg_desc_x0_o;
    dbg_y0_ = top_->dbg_desc_y0_o;
    dbg_done_ = top_->dbg_watch_done_o;
  }

  void dump() {
    // Called at both clock phases; the low phase is the settled state before the rising edge.
    if (!top_->clk_i) sample_pre();
#if VM_TRACE
    if (tfp_ && tracing_) tfp_->dump(ctx_->time());
#endif
  }

  // FST window: a cycle range, or the life of one tile (handed out .. last pixel written).
  void tile_window() {
#if VM_TRACE
    if (!tfp_) return;
    if (o_.wave_tx >= 0) {
      const int x0 = o_.wave_tx * o_.tile, y0 = o_.wave_ty * o_.tile;
      if (!tracing_ && !tile_traced_ && dbg_fire_ && dbg_x0_ == x0 && dbg_y0_ == y0) {
        tracing_ = true;
        trace_from_ = cycle_;
      }
      if (tracing_ && dbg_done_) {
        tile_traced_ = true;
        tail_ = 20;  // a few cycles after, for the last bursts
      }
      if (tile_traced_ && tracing_ && tail_-- == 0) {
        tracing_ = false;
        std::fprintf(stderr, "harness: waves: tile (%d,%d) cycles %llu..%llu -> %s\n", o_.wave_tx,
                     o_.wave_ty, (unsigned long long)trace_from_, (unsigned long long)cycle_,
                     o_.waves.c_str());
      }
    } else {
      tracing_ = cycle_ >= o_.wave_from && cycle_ <= o_.wave_to;
    }
#endif
  }

  VerilatedContext *ctx_;
  uint64_t half_ = 1;  // half a clock period in time steps (set once the model exists)
  const Options &o_;
  std::mt19937 rng_;
  std::unique_ptr<Vmsr_sim_top> top_;
#if VM_TRACE
  std::unique_ptr<VerilatedFstC> tfp_;
#endif
  bool tracing_ = false, tile_traced_ = false;
  int tail_ = 0;
  uint64_t trace_from_ = 0;
  bool dbg_fire_ = false, dbg_done_ = false;
  unsigned dbg_x0_ = 0, dbg_y0_ = 0;
  uint64_t cycle_ = 0, pixels_written_ = 0;
  std::vector<uint8_t> mem_;
  uint32_t fb_base_, fb_stride_, src_base_, src_stride_;
  std::deque<Burst> aw_q_;
  std::deque<unsigned> b_q_;
  unsigned w_beat_ = 0;
  bool burst_err_ = false, bvalid_ = false, write_error_ = false;
  bool mem_awready_ = true, mem_wready_ = true;
};

// Frame k's file of a sequence: the path is a printf pattern of the frame number (one frame:
// the path as given).
std::string frame_file(const std::string &pattern, long frames, long k) {
  if (frames == 1 || pattern.empty()) return pattern;
  char buf[4096];
  std::snprintf(buf, sizeof buf, pattern.c_str(), k);
  return buf;
}

bool write_ppm(const std::string &path, const Sim &s, int w, int h) {
  FILE *f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fprintf(f, "P6\n%d %d\n255\n", w, h);
  std::vector<uint8_t> row(3 * w);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      uint32_t v = s.pixel(x, y);
      row[3 * x] = v >> 16;
      row[3 * x + 1] = v >> 8;
      row[3 * x + 2] = v;
    }
    std::fwrite(row.data(), 1, row.size(), f);
  }
  return std::fclose(f) == 0;
}

// The depth channel's plane: msr_sim_top's monitor (a DEPTH_EN build) calls msr_dpi_depth_pixel
// for every pixel as it leaves its engine; -1 marks a pixel that never came.
std::vector<int32_t> g_depth;
int g_depth_w = 0, g_depth_h = 0;

void depth_reset(int w, int h) {
  g_depth.assign(static_cast<size_t>(w) * h, -1);
  g_depth_w = w;
  g_depth_h = h;
}

// 16-bit binary PGM (maxval 65535, big-endian samples); false if a pixel has no depth.
bool write_depth_pgm(const std::string &path, int w, int h) {
  for (int32_t v : g_depth)
    if (v < 0) return false;
  FILE *f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fprintf(f, "P5\n%d %d\n65535\n", w, h);
  std::vector<uint8_t> row(2 * static_cast<size_t>(w));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int32_t v = g_depth[static_cast<size_t>(y) * w + x];
      row[2 * x] = uint8_t(v >> 8);
      row[2 * x + 1] = uint8_t(v & 0xff);
    }
    std::fwrite(row.data(), 1, row.size(), f);
  }
  return std::fclose(f) == 0;
}

bool write_pgm(const std::string &path, const Sim &s, int w, int h) {
  FILE *f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fprintf(f, "P5\n%d %d\n255\n", w, h);
  std::vector<uint8_t> row(w);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) row[x] = s.code(x, y);
    std::fwrite(row.data(), 1, row.size(), f);
  }
  return std::fclose(f) == 0;
}

}  // namespace

extern "C" void msr_dpi_depth_pixel(int x, int y, int invz) {
  if (x < 0 || y < 0 || x >= g_depth_w || y >= g_depth_h) {
    std::fprintf(stderr, "harness: error: depth of pixel (%d, %d) outside the frame\n", x, y);
    std::exit(kExitFail);
  }
  g_depth[static_cast<size_t>(y) * g_depth_w + x] = invz;
}

int main(int argc, char **argv) {
  const Options o = parse(argc, argv);
  auto ctx = std::make_unique<VerilatedContext>();
  ctx->commandArgs(argc, argv);
  ctx->randSeed(static_cast<int>(o.seed));
  if (o.width < 1 || o.height < 1 || o.width > 4096 || o.height > 4096)
    usage("--width and --height must be 1..4096 (the harness sizes its memory from them)");

  int rc = kExitOk;
  const auto t0 = std::chrono::steady_clock::now();
  uint64_t cycles_run = 0;
  {
    Sim sim(ctx.get(), o);
    sim.open_waves();
    sim.reset();

    uint32_t scale_prev = 0;   // the last frame's SCALE_OUT (a budget sequence)
    for (long k = 0; k < o.frames && rc == kExitOk; ++k) {
    depth_reset(o.width, o.height);
    if (!o.cameras.empty()) {
      char err[512] = {0};
      if (!msr_dpi_set_view(o.cameras[k].c_str(), err, sizeof err)) {
        std::fprintf(stderr, "harness: error: frame %ld: %s\n", k, err);
        return kExitFail;
      }
    }
    // Program the frame as a driver would, then start and poll. In a budget sequence each
    // frame after the first starts from the last SCALE_OUT with the seeded law.
    const long scale_init = (k > 0 && o.budget) ? long(scale_prev) : o.scale_init;
    const long seeded = (k > 0 && o.budget) ? 1 : o.seeded;
    sim.write_reg(REG(FRAME_SIZE),
                  (uint32_t(o.width) << MSR_REGS__FRAME_SIZE__WIDTH_bp) |
                      (uint32_t(o.height) << MSR_REGS__FRAME_SIZE__HEIGHT_bp));
    sim.write_reg(REG(CONFIG), (uint32_t(o.tile) << MSR_REGS__CONFIG__TILE_bp) |
                            (uint32_t(o.levels) << MSR_REGS__CONFIG__LEVELS_bp) |
                            (uint32_t(o.metric) << MSR_REGS__CONFIG__METRIC_bp) |
                            (uint32_t(o.rule) << MSR_REGS__CONFIG__RULE_bp));
    sim.write_reg(REG(THRESH), (uint32_t(o.thr[0]) << MSR_REGS__THRESH__THR1_bp) |
                            (uint32_t(o.thr[1]) << MSR_REGS__THRESH__THR2_bp) |
                            (uint32_t(o.thr[2]) << MSR_REGS__THRESH__THR3_bp));
    sim.write_reg(REG(FOV_GAIN), uint32_t(o.fov_gain));
    // this frame's gaze: its --gazes line, else --gaze
    const bool own_gaze = !o.gazes.empty() && o.gazes[k].first >= 0;
    const long gaze_x = own_gaze ? o.gazes[k].first : o.gaze_x;
    const long gaze_y = own_gaze ? o.gazes[k].second : o.gaze_y;
    sim.write_reg(REG(GAZE), gaze_x < 0 ? 0u
                                        : MSR_REGS__GAZE__EN_bm |
                                              ((uint32_t(gaze_x) << MSR_REGS__GAZE__X_bp) & MSR_REGS__GAZE__X_bm) |
                                              ((uint32_t(gaze_y) << MSR_REGS__GAZE__Y_bp) & MSR_REGS__GAZE__Y_bm));
    sim.write_reg(REG(FB_BASE), o.fb_base >= 0 ? uint32_t(o.fb_base) : sim.fb_base());
    sim.write_reg(REG(FB_STRIDE), sim.fb_stride());
    sim.write_reg(REG(SRC_BASE), sim.src_base());
    sim.write_reg(REG(SRC_STRIDE), sim.src_stride());
    sim.write_reg(REG(SRC_CTRL), MSR_REGS__SRC_CTRL__ENABLE_bm);
    // Field values outside the register's bits are masked off as a bus write would cut them;
    // the hardware checks what arrives (a budget below the grid: STATUS.ERROR 14).
    sim.write_reg(REG(BUDGET), uint32_t(o.budget) & MSR_REGS__BUDGET__PIXELS_bm);
    sim.write_reg(REG(BUDGET_CTRL),
                  ((uint32_t(scale_init) << MSR_REGS__BUDGET_CTRL__SCALE_INIT_bp) &
                   MSR_REGS__BUDGET_CTRL__SCALE_INIT_bm) |
                      ((uint32_t(o.prior_shift) << MSR_REGS__BUDGET_CTRL__PRIOR_SHIFT_bp) &
                       MSR_REGS__BUDGET_CTRL__PRIOR_SHIFT_bm) |
                      ((uint32_t(seeded) << MSR_REGS__BUDGET_CTRL__SEEDED_bp) &
                       MSR_REGS__BUDGET_CTRL__SEEDED_bm));
    sim.write_reg(REG(CTRL), MSR_REGS__CTRL__START_bm | MSR_REGS__CTRL__IRQ_EN_bm);

    const uint64_t pixels = uint64_t(o.width) * o.height;
    const uint64_t timeout = o.timeout ? o.timeout : 100000 + 200 * pixels;
    const uint64_t start_cycle = sim.cycle();
    auto last_print = std::chrono::steady_clock::now();
    const bool tty = isatty(2);  // the progress line rewrites itself: terminals only
    uint32_t status = 0;
    for (;;) {
      for (int i = 0; i < 512; ++i) sim.tick();
      status = sim.read_reg(REG(STATUS));
      const bool done = status & MSR_REGS__STATUS__DONE_bm;
      const unsigned err = (status & MSR_REGS__STATUS__ERROR_bm) >> MSR_REGS__STATUS__ERROR_bp;
      const bool busy = status & MSR_REGS__STATUS__BUSY_bm;
      if (done || (err && !busy)) break;
      if (sim.cycle() - start_cycle > timeout) {
        std::fprintf(stderr, "\nharness: error: timeout after %llu cycles (%llu of %llu pixels written)\n",
                     (unsigned long long)(sim.cycle() - start_cycle),
                     (unsigned long long)sim.pixels_written(), (unsigned long long)pixels);
        return kExitFail;
      }
      const auto now = std::chrono::steady_clock::now();
      if (!o.quiet && tty && now - last_print > std::chrono::milliseconds(500)) {
        last_print = now;
        const double secs = std::chrono::duration<double>(now - t0).count();
        std::fprintf(stderr, "\rharness: cycle %llu, %5.1f%% of pixels written, %.2f Mcycles/s ",
                     (unsigned long long)sim.cycle(), 100.0 * sim.pixels_written() / pixels,
                     sim.cycle() / secs / 1e6);
      }
    }
    const unsigned err = (status & MSR_REGS__STATUS__ERROR_bm) >> MSR_REGS__STATUS__ERROR_bp;
    if (!o.quiet && tty) std::fprintf(stderr, "\r%78s\r", "");
    // Performance counters, read over the register port like a driver would.
    uint32_t perf_cycles = sim.read_reg(REG(PERF_CYCLES));
    uint32_t traced[4], interp[3];
    for (int k = 0; k < 4; ++k) traced[k] = sim.read_reg(REG(PERF_TRACED) + 4 * k);
    for (int k = 0; k < 3; ++k) interp[k] = sim.read_reg(REG(PERF_INTERP) + 4 * k);
    uint32_t rstall = sim.read_reg(REG(PERF_RENDER_STALL)), mstall = sim.read_reg(REG(PERF_MEM_STALL));
    const uint32_t bctrl = sim.read_reg(REG(BUDGET_CTRL));
    const unsigned scale_out =
        (bctrl & MSR_REGS__BUDGET_CTRL__SCALE_OUT_bm) >> MSR_REGS__BUDGET_CTRL__SCALE_OUT_bp;
    const bool scale_out_valid = bctrl & MSR_REGS__BUDGET_CTRL__SCALE_OUT_VALID_bm;
    scale_prev = scale_out;
    // DONE is write-1-to-clear, as a driver acknowledges a frame before the next START.
    sim.write_reg(REG(STATUS), MSR_REGS__STATUS__DONE_bm);
    cycles_run = sim.cycle();
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    if (err) {
      std::fprintf(stderr, "harness: error: STATUS.ERROR = %u\n", err);
      rc = kExitFail;
    }
    const std::string frame_out = frame_file(o.frame_out, o.frames, k);
    const std::string source_out = frame_file(o.source_out, o.frames, k);
    if (!frame_out.empty() && !write_ppm(frame_out, sim, o.width, o.height)) {
      std::fprintf(stderr, "harness: error: cannot write %s\n", frame_out.c_str());
      rc = kExitFail;
    }
    const std::string depth_out = frame_file(o.depth_out, o.frames, k);
    if (!depth_out.empty() && !Vmsr_sim_top___024root::msr_sim_top__DOT__DEPTH_EN) {
      std::fprintf(stderr, "harness: error: --depth: this harness has no depth channel (build it with make sim DEPTH=1)\n");
      rc = kExitFail;
    } else if (!depth_out.empty() && !write_depth_pgm(depth_out, o.width, o.height)) {
      std::fprintf(stderr, "harness: error: cannot write %s (or a pixel's depth never came)\n", depth_out.c_str());
      rc = kExitFail;
    }
    if (!source_out.empty() && !write_pgm(source_out, sim, o.width, o.height)) {
      std::fprintf(stderr, "harness: error: cannot write %s\n", source_out.c_str());
      rc = kExitFail;
    }
    if (!o.stats_out.empty()) {
      FILE *f = std::fopen(o.stats_out.c_str(), k == 0 ? "w" : "a");
      if (!f) {
        std::fprintf(stderr, "harness: error: cannot write %s\n", o.stats_out.c_str());
        rc = kExitFail;
      } else {
        // The facts the scripts need come from here, not from copies of them: the build's
        // parameters, the memory layout this harness programmed, the frame's register values.
        using Root = Vmsr_sim_top___024root;
        // the gaze written to GAZE (with EN), or null: GAZE 0, the frame centre
        const std::string gaze_json = gaze_x < 0 ? std::string("null")
                                                 : "[" + std::to_string(gaze_x) + ", " +
                                                       std::to_string(gaze_y) + "]";
        std::fprintf(f,
                     "{\"frame\": %ld, \"cycles\": %u, \"sim_cycles_total\": %llu, \"sim_seconds\": %.4f, "
                     "\"sim_cycles_per_second\": %.1f, \"status\": %u, \"error\": %u, "
                     "\"traced_initial\": %u, \"traced_level1\": %u, \"traced_level2\": %u, "
                     "\"traced_level3\": %u, \"interpolated_level1\": %u, \"interpolated_level2\": %u, "
                     "\"interpolated_level3\": %u, \"render_stall_cycles\": %u, \"memory_stall_cycles\": %u,\n"
                     " \"gaze\": %s,\n"
                     " \"budget\": {\"pixels\": %ld, \"scale_init\": %ld, \"prior_shift\": %ld, \"seeded\": %ld, "
                     "\"scale_out\": %u, \"scale_out_valid\": %s},\n"
                     " \"build\": {\"num_engines\": %u, \"max_outstanding\": %u, \"num_ctx\": %u, "
                     "\"budget_en\": %u, \"depth_en\": %u, \"rd_lat\": %u, \"tile_limit\": %u, \"buf_cycle\": %u, "
                     "\"axi_beat_bytes\": %u},\n"
                     " \"layout\": {\"fb_base\": %lld, \"fb_stride\": %u, \"src_base\": %u, \"src_stride\": %u},\n"
                     " \"params\": {\"width\": %d, \"height\": %d, \"tile\": %d, \"levels\": %d, "
                     "\"thr\": [%d, %d, %d], \"metric\": \"%s\", \"fov_gain\": %d, \"rule\": %d}}\n",
                     k, perf_cycles, (unsigned long long)cycles_run, secs, cycles_run / secs, status, err,
                     traced[0], traced[1], traced[2], traced[3], interp[0], interp[1], interp[2], rstall,
                     mstall, gaze_json.c_str(), o.budget, scale_init, o.prior_shift, seeded, scale_out,
                     scale_out_valid ? "true" : "false", unsigned(Root::msr_sim_top__DOT__NUM_ENGINES),
                     unsigned(Root::msr_sim_top__DOT__MAX_OUTSTANDING), unsigned(Root::msr_sim_top__DOT__NUM_CTX),
                     unsigned(Root::msr_sim_top__DOT__BUDGET_EN), unsigned(Root::msr_sim_top__DOT__DEPTH_EN),
                     unsigned(Root::msr_sim_top__DOT__RD_LAT),
                     unsigned(Root::msr_sim_top__DOT__TILE_LIMIT),
                     unsigned(Root::msr_sim_top__DOT__BUF_CYCLE), kBeatBytes, o.fb_base >= 0 ? o.fb_base : (long long)sim.fb_base(), sim.fb_stride(),
                     sim.src_base(), sim.src_stride(), o.width, o.height, o.tile, o.levels, o.thr[0], o.thr[1],
                     o.thr[2], o.metric ? "sum" : "max", o.fov_gain, o.rule);
        std::fclose(f);
      }
    }
    if (!o.quiet)
      std::fprintf(stderr, "harness: %dx%d in %u cycles (%.2f cycles/pixel), %.2f s, %.2f Mcycles/s\n",
                   o.width, o.height, perf_cycles, double(perf_cycles) / pixels, secs,
                   cycles_run / secs / 1e6);
    if (sim.write_error()) {
      std::fprintf(stderr, "harness: error: the memory answered a write with SLVERR\n");
      rc = kExitFail;
    }
    }  // frames
  }
  return rc;
}
