// SPDX-License-Identifier: Apache-2.0
// svpwm console firmware for the LiteX SoC (fpga/litex): a line console on the UART that sets up and runs
// the core through its registers. Every register, field, offset and reset value comes from the generated
// sw/svpwm_regs.h (rdl/svpwm.rdl); the core's base address from the build's generated/mem.h (SVPWM_BASE),
// its MinPeriod from generated/soc.h (model/svpwm_model/fixed.py). Units use the core's CLK_HZ and CONFIG,
// as scripts/svpwmctl.py does, and values out of range are refused with a message, never clamped.
// Commands (help lists them): freq HZ, m INDEX, period CLOCKS, fsw HZ, dt US, mode NAME, start, stop,
// status, clear, ramp MS. A trip (STATUS.tripped) is reported as soon as it happens.
// Restrictions: one core; registers are written one at a time (32-bit accesses, never byte lanes), so a
// change of several registers while running may straddle a load point (see rtl/svpwm_wb.sv). The ROM is
// 8 KiB (fpga/litex/README.md): a small printf of its own, the UART and timer0 polled (no interrupts).
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <libbase/uart.h>
#include <generated/csr.h>
#include <generated/mem.h>
#include <generated/soc.h>

#include "svpwm_regs.h"

// A register of the generated map as a 32-bit location (the packed svpwm_t would be accessed byte-wise)
#define REG(r)          (*(volatile uint32_t *)(SVPWM_BASE + offsetof(svpwm_t, r)))
#define GET(r, f, v)    (((uint32_t)(v) & SVPWM__##r##__##f##_bm) >> SVPWM__##r##__##f##_bp)
#define PUT(r, f, v)    (((uint32_t)(v) << SVPWM__##r##__##f##_bp) & SVPWM__##r##__##f##_bm)
#define FIELD(r, f)     GET(r, f, REG(r))
// read-modify-write of one field
#define SETF(r, f, v)   (REG(r) = (REG(r) & ~(uint32_t)SVPWM__##r##__##f##_bm) | PUT(r, f, v))

// CTRL.mode encodings (docs/registers.md, scripts/svpwmctl.py MODES)
static const char *const mode_names[] = {"freq", "vf", "polar", "alphabeta", "dq"};
#define N_MODES ((int)(sizeof(mode_names) / sizeof(mode_names[0])))
// the feature each mode needs (FEATURES.features; index = the mode code)
static const uint32_t mode_feat[] = {SVPWM_FEAT_FREQ, SVPWM_FEAT_VF, SVPWM_FEAT_POLAR, SVPWM_FEAT_AB, SVPWM_FEAT_DQ};

// ------------------------------------------------------------------------------------------ output
// say(): a small printf for the console: %d int32, %x uint32 as 0x%08x, %s string, %3 / %5 an int32
// holding a value * 10^3 / 10^5, printed with up to that many decimals ("\n" -> "\r\n")
static void out_c(char c) {
  if (c == '\n') uart_write('\r');
  uart_write(c);
}

static void out_dec(uint32_t v, int width) {
  char b[12];
  int i = 0;
  do {
    b[i++] = (char)('0' + v % 10);
    v /= 10;
  } while (v || i < width);
  while (i) out_c(b[--i]);
}

static void say(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  for (; *fmt; fmt++) {
    if (*fmt != '%') {
      out_c(*fmt);
      continue;
    }
    char f = *++fmt;
    if (f == 's') {
      for (const char *s = va_arg(ap, const char *); *s; s++) out_c(*s);
      continue;
    }
    int32_t v = va_arg(ap, int32_t);
    if (f == 'x') {
      out_c('0');
      out_c('x');
      for (int i = 28; i >= 0; i -= 4) out_c("0123456789abcdef"[((uint32_t)v >> i) & 15]);
      continue;
    }
    uint32_t a = v < 0 ? -(uint32_t)v : (uint32_t)v, p = 1;
    int dec = f == 'd' ? 0 : f - '0';
    for (int i = 0; i < dec; i++) p *= 10;
    if (v < 0) out_c('-');
    out_dec(a / p, 1);
    uint32_t frac = a % p;
    if (frac) {
      while (frac % 10 == 0) { frac /= 10; dec--; }
      out_c('.');
      out_dec(frac, dec);
    }
  }
  va_end(ap);
}

static int err(const char *msg, const char *arg) {
  say("error: %s%s\n", msg, arg ? arg : "");
  return -1;
}

// ------------------------------------------------------------------------------------------ numbers
// "[-]digits[.digits]" -> value * 10^dec as int32 (at most dec decimals, at most 9 digits); 0 on success
static int parse_fixed(const char *s, int dec, int32_t *res) {
  int neg = 0, n = 0, nfrac = -1;
  int32_t v = 0;
  if (*s == '-') { neg = 1; s++; }
  for (; *s; s++) {
    if (*s == '.' && nfrac < 0) { nfrac = 0; continue; }
    if (*s < '0' || *s > '9' || ++n > 9) return -1;
    if (nfrac >= 0 && ++nfrac > dec) return -1;
    v = v * 10 + (*s - '0');
  }
  if (!n) return -1;
  for (nfrac = nfrac < 0 ? 0 : nfrac; nfrac < dec; nfrac++) {
    if (v > 214748364) return -1;
    v *= 10;
  }
  *res = neg ? -v : v;
  return 0;
}

// a * b / c rounded half away from zero (c > 0), as svpwmctl's round_half_away; the one 64-bit helper
// (restoring division, bit by bit: a few instructions instead of compiler-rt's 64-bit divider in the ROM)
static int64_t __attribute__((noinline)) muldiv(int64_t a, int64_t b, int64_t c) {
  int64_t x = a * b;
  uint64_t n = 2 * (x < 0 ? -(uint64_t)x : (uint64_t)x) + (uint64_t)c, d = 2 * (uint64_t)c, r = 0, q = 0;
  for (int i = 63; i >= 0; i--) {
    r = (r << 1) | ((n >> i) & 1);
    q <<= 1;
    if (r >= d) {
      r -= d;
      q |= 1;
    }
  }
  return x < 0 ? -(int64_t)q : (int64_t)q;
}

// ------------------------------------------------------------------------------------------ the core
static uint32_t clk_hz(void) { return REG(CLK_HZ); }
static int64_t freq_den(void) { return (int64_t)6 << FIELD(CONFIG, PHASE_WIDTH); }   // LSBs per Hz * CLK_HZ
static int32_t freq_lim(void) { return (1 << (FIELD(CONFIG, FREQ_WIDTH) - 1)) - 1; }  // the core's FreqMax
// the core's build (FEATURES.features, the SVPWM_FEAT_* bits of svpwm_regs.h): what is not built reads 0
static int has(uint32_t feat) { return (FIELD(FEATURES, FEATURES) & feat) != 0; }
static int32_t min_period(void) { return SVPWM_MIN_PERIOD; }   // the SoC's build's MinPeriod (svpwm_soc.py)
// frequency word -> mHz and f_sw of a half period -> mHz
static int32_t freq_mhz(int32_t w) { return (int32_t)muldiv(w, (int64_t)clk_hz() * 1000, freq_den()); }
static int32_t fsw_mhz(int32_t p) { return (int32_t)muldiv(clk_hz(), 500, p); }

static int freq_word(int32_t mhz, int32_t *w) {
  int32_t lim = freq_lim();
  int64_t wl = muldiv(mhz, freq_den(), (int64_t)clk_hz() * 1000);
  if (wl < -lim || wl > lim) {
    say("error: %3 Hz is out of range: |f| <= %3 Hz (frequency word +-%d at %d Hz)\n", mhz,
        freq_mhz(lim), lim, clk_hz());
    return -1;
  }
  *w = (int32_t)wl;
  return 0;
}

static int period_ok(int32_t p) {
  int32_t top = (1 << FIELD(CONFIG, CNT_WIDTH)) - 1;
  int32_t dtmp = 2 * (int32_t)(FIELD(DT, DT) + FIELD(MP, MP));
  int32_t low = min_period() > dtmp ? min_period() : dtmp;
  if (p >= low && p <= top) return 0;
  say("error: half period %d is out of range %d .. %d clocks (f_sw %3 .. %3 Hz)\n", p, low, top, fsw_mhz(top),
      fsw_mhz(low));
  return -1;
}

static void set_period(int32_t p) {
  SETF(PERIOD, PERIOD, p);
  say("PERIOD = %d clocks (f_sw %3 Hz)\n", p, fsw_mhz(p));
}

// ------------------------------------------------------------------------------------------ commands
static int cmd_freq(int32_t mhz) {
  int32_t w;
  if (freq_word(mhz, &w)) return -1;
  SETF(FREQ, FREQ, (uint32_t)w);
  say("FREQ = %d (%3 Hz)\n", w, freq_mhz(w));
  return 0;
}

static int cmd_m(int32_t e5) {
  int32_t w = (int32_t)muldiv(e5, 0x8000, 100000);
  if (w < 0 || w > 0xFFFF) return err("m out of range 0 .. 1.99997", 0);
  SETF(M, M, w);
  say("M = %x (m = %5)\n", w, (int32_t)muldiv(w, 100000, 0x8000));
  return 0;
}

static int cmd_period(int32_t p) {
  if (period_ok(p)) return -1;
  set_period(p);
  return 0;
}

static int cmd_fsw(int32_t mhz) {
  if (mhz <= 0) return err("f_sw must be > 0", 0);
  int32_t p = (int32_t)muldiv(clk_hz(), 500, mhz);
  if (period_ok(p)) return -1;
  set_period(p);
  return 0;
}

static int cmd_dt(int32_t ns) {
  if (ns < 0) return err("dead time must be >= 0", 0);
  int32_t top = (1 << FIELD(CONFIG, DT_WIDTH)) - 1;
  int64_t n = muldiv(ns, clk_hz(), 1000000000);
  if (n > top) {
    say("error: dead time %3 us is out of range: at most %d clocks (%3 us)\n", ns, top,
        (int32_t)muldiv(top, 1000000000, clk_hz()));
    return -1;
  }
  if (ns > 0 && n == 0) return err("dead time < half a clock: it would be 0", 0);
  if (FIELD(STATUS, LOCKED)) return err("dead time is locked (CTRL.lock) until reset", 0);
  int32_t period = FIELD(PERIOD, PERIOD), mp = FIELD(MP, MP);
  if (period < 2 * (n + mp)) {
    say("error: dead time %d clocks needs PERIOD >= 2 (DT + MP) = %d, PERIOD is %d\n", (int32_t)n,
        (int32_t)(2 * (n + mp)), period);
    return -1;
  }
  SETF(DT, DT, n);
  say("DT = %d clocks (%3 us)\n", (int32_t)n, (int32_t)muldiv(n, 1000000000, clk_hz()));
  return 0;
}

static int str_eq(const char *a, const char *b) {
  while (*a && *a == *b) { a++; b++; }
  return *a == *b;
}

static int cmd_mode(const char *a) {
  for (int i = 0; i < N_MODES; i++) {
    if (str_eq(a, mode_names[i])) {
      if (!has(mode_feat[i])) return err("not in this build (FEATURES): mode ", a);
      SETF(CTRL, MODE, i);
      say("CTRL.mode = %s\n", mode_names[i]);
      return 0;
    }
  }
  return err("mode: freq|vf|polar|alphabeta|dq, not ", a);
}

static int dt_set(void) {
  if (FIELD(DT, DT)) return 1;
  err("DT is 0: set dt first", 0);
  return 0;
}

static int cmd_clear(void) {
  SETF(CTRL, FAULT_CLEAR, 1);
  uint32_t st = REG(STATUS);
  if (GET(STATUS, TRIPPED, st))
    return err(GET(STATUS, FAULT, st) ? "still tripped: the fault input is active"
                                      : "still tripped after CTRL.fault_clear", 0);
  say("fault cleared\n");
  return 0;
}

static void cmd_status(void) {
  uint32_t st = REG(STATUS), ctrl = REG(CTRL), mode = GET(CTRL, MODE, ctrl);
  int32_t fw = (int32_t)(GET(FREQ, FREQ, REG(FREQ)) << 8) >> 8;   // FREQ is a signed 24-bit field
  int32_t period = FIELD(PERIOD, PERIOD);
  say("running %d tripped %d fault %d sat %d cfg_err %d period_clamp %d freq_clamp %d locked %d\n",
      GET(STATUS, RUNNING, st), GET(STATUS, TRIPPED, st), GET(STATUS, FAULT, st), GET(STATUS, SAT, st),
      GET(STATUS, CFG_ERR, st), GET(STATUS, PERIOD_CLAMP, st), GET(STATUS, FREQ_CLAMP, st),
      GET(STATUS, LOCKED, st));
  say("sector %d en %d mode %s\nfreq %3 Hz (word %d) m %5 period %d clocks (f_sw %3 Hz) dt %d clocks\n"
      "CLK_HZ %d (FEATURES %x)\n",
      GET(STATUS, SECTOR, st), GET(CTRL, EN, ctrl), mode < (uint32_t)N_MODES ? mode_names[mode] : "invalid",
      freq_mhz(fw), fw, (int32_t)muldiv(FIELD(M, M), 100000, 0x8000), period, period ? fsw_mhz(period) : 0,
      FIELD(DT, DT), clk_hz(), REG(FEATURES));
}

static uint32_t tripped_seen;

static void report_trip(void) {
  uint32_t st = REG(STATUS), t = GET(STATUS, TRIPPED, st);
  if (t && !tripped_seen)
    say("\nFAULT: tripped, gates safe (fault input %d)\n",
        GET(STATUS, FAULT, st));
  tripped_seen = t;
}

// V/f ramp 0 -> 50 Hz in `ms`: the core's V/f law (CTRL.mode vf, VF_BOOST 0, VF_MMAX = M, VF_SLOPE such
// that m reaches M at 50 Hz), FREQ stepped in RAMP_STEPS equal steps on timer0's period.
#define RAMP_STEPS 50
static int cmd_ramp(int32_t ms) {
  int32_t w50;
  if (ms < 1 || ms > 60000) return err("ramp time out of range 1 .. 60000 ms", 0);
  if (!has(SVPWM_FEAT_VF)) return err("not in this build (FEATURES): ramp (needs vf)", 0);
  if (!dt_set()) return -1;
  int32_t m = FIELD(M, M);
  if (m == 0) return err("M is 0: set m (the index at 50 Hz) first", 0);
  if (freq_word(50000, &w50)) return -1;
  int32_t fa50 = w50 >> (FIELD(CONFIG, FREQ_WIDTH) - 17);
  int32_t slope = fa50 ? (int32_t)muldiv(m, 256, fa50) : 0x10000;
  if (slope > 0xFFFF) return err("VF_SLOPE overflow", 0);
  uint32_t step = (uint32_t)muldiv(CONFIG_CLOCK_FREQUENCY / 1000, ms, RAMP_STEPS);
  // step k's word, round(k * w50 / RAMP_STEPS) = (2 k w50 + RAMP_STEPS) / (2 RAMP_STEPS), kept as a
  // quotient and a remainder and advanced by additions only: on SERV a 64-bit division per step would
  // take longer than a short ramp's step
  uint32_t den = 2 * RAMP_STEPS, inc = 2 * (uint32_t)w50, dq = inc / den, dr = inc % den;
  uint32_t q = 0, r = RAMP_STEPS;                                   // k = 0: (0 + RAMP_STEPS) / den
  REG(FREQ) = 0;
  REG(VF_BOOST) = 0;
  REG(VF_MMAX) = PUT(VF_MMAX, VF_MMAX, m);
  REG(VF_SLOPE) = PUT(VF_SLOPE, VF_SLOPE, slope);
  SETF(CTRL, MODE, 1);
  SETF(CTRL, EN, 1);
  timer0_en_write(0);
  timer0_load_write(step);
  timer0_reload_write(step);
  timer0_ev_pending_write(timer0_ev_pending_read());
  timer0_en_write(1);
  for (int k = 1; k <= RAMP_STEPS; k++) {
    q += dq;
    r += dr;
    if (r >= den) {
      r -= den;
      q++;
    }
    while (!(timer0_ev_pending_read() & 1)) {
      if (FIELD(STATUS, TRIPPED)) {
        timer0_en_write(0);
        report_trip();
        return err("ramp aborted: tripped", 0);
      }
    }
    timer0_ev_pending_write(1);
    SETF(FREQ, FREQ, q);
  }
  timer0_en_write(0);
  say("ramp: 0 -> 50 Hz in %d ms, V/f up to m %5: done, FREQ = %d (%3 Hz)\n", ms,
      (int32_t)muldiv(m, 100000, 0x8000), w50, freq_mhz(w50));
  return 0;
}

// ------------------------------------------------------------------------------------------ console
static const char help_text[] =
    "freq HZ|m M|period N|fsw HZ|dt US|mode NAME|start|stop|status|clear|ramp MS (V/f to 50 Hz)\n";

#define LINE_MAX 64

static void execute(char *line) {
  char *cmd = line, *arg = 0;
  while (*cmd == ' ') cmd++;
  for (char *p = cmd; *p; p++) {
    if (*p == ' ') {
      *p = 0;
      if (!arg) arg = p + 1;
    }
  }
  while (arg && *arg == ' ') arg++;
  if (!*cmd) return;
  if (str_eq(cmd, "start")) {
    if (dt_set()) {
      SETF(CTRL, EN, 1);
      say("started\n");
    }
    return;
  }
  if (str_eq(cmd, "stop")) {
    SETF(CTRL, EN, 0);
    say("stopped\n");
    return;
  }
  if (str_eq(cmd, "status")) { cmd_status(); return; }
  if (str_eq(cmd, "clear")) { cmd_clear(); return; }
  if (str_eq(cmd, "help")) { say(help_text); return; }
  if (str_eq(cmd, "mode")) { cmd_mode(arg ? arg : ""); return; }
  // numeric commands: name, decimals of the value (units: Hz, -, clocks, Hz, us, ms)
  static const char *const names[] = {"freq", "m", "period", "fsw", "dt", "ramp"};
  static const uint8_t decimals[] = {3, 5, 0, 3, 3, 0};
  static int (*const cmds[])(int32_t) = {cmd_freq, cmd_m, cmd_period, cmd_fsw, cmd_dt, cmd_ramp};
  for (unsigned i = 0; i < sizeof(names) / sizeof(names[0]); i++) {
    if (str_eq(cmd, names[i])) {
      int32_t v;
      if (!arg || parse_fixed(arg, decimals[i], &v)) {
        say("error: %s needs a number with at most %d decimals, not '%s'\n", cmd, decimals[i], arg ? arg : "");
        return;
      }
      cmds[i](v);
      return;
    }
  }
  err("unknown command (help): ", cmd);
}

void isr(void);
void isr(void) {}    // no interrupts: the UART is polled (UART_POLLING), timer0 is polled

int main(void) {
  static char line[LINE_MAX];
  int n = 0;
  uart_init();
  say("\nsvpwm console: core ID %x, map %d.%d, CLK_HZ %d, base %x\n", REG(ID), FIELD(VERSION, MAJOR),
      FIELD(VERSION, MINOR), clk_hz(), SVPWM_BASE);
  say("svpwm> ");
  for (;;) {
    report_trip();
    if (!uart_read_nonblock()) continue;
    char c = uart_read();
    if (c == '\r' || c == '\n') {
      say("\n");
      line[n] = 0;
      execute(line);
      n = 0;
      say("svpwm> ");
    } else if (c == 0x08 || c == 0x7f) {
      if (n) {
        n--;
        say("\b \b");
      }
    } else if (n < LINE_MAX - 1 && c >= ' ') {
      line[n++] = c;
      out_c(c);
    }
  }
  return 0;
}
