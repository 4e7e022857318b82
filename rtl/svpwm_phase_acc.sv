// SPDX-License-Identifier: Apache-2.0
// svpwm_phase_acc: phase accumulator that keeps the sector (0..5) and the in-sector angle directly.
// AVR495 sec. 4.3: theta' is integrated and confined to [0, 60 deg); the sector is a modulo-6 counter
// stepped each time theta' wraps, so no division by 6 is needed. Verma's sector + angle + fraction word
// is the same idea: here the angle is a PhaseWidth-bit binary fraction of 60 deg.
// Parameters: PhaseWidth - angle fraction bits; FreqWidth - signed step width (FreqWidth < PhaseWidth);
//   CarrySelect - 1: the carry-select adder below (svpwm_core uses it but in its tiny build), 0: one
//   PhaseWidth + 1 bit carry chain (40 fewer logic cells). On the iCEBreaker build at 48 MHz the chain was the worst
//   path at nextpnr seeds 1 and 3 (step_i's register -> 34 carries -> angle_q, 20.57 ns); with
//   CarrySelect 1 that build gave 48.10 / 49.62 / 48.11 MHz at seeds 1 / 2 / 3 (+40 LC), its worst
//   paths elsewhere (the low chain then ends at the upper bits' clock enable, run_i && neg != c:
//   19.2-20.3 ns).
//   Both give the same angle and sector in every clock.
// One LSB of step_i is 60 deg / 2^PhaseWidth per clock, i.e. f_out = step * f_clk / (6 * 2^PhaseWidth).
// Latency: none: angle_o is a register; sector_o is the sector register stepped by the wrap registered
// in the clock before (two LUT levels from flip-flops). Negative steps rotate backwards, zero stands still.
// Timing (CarrySelect 1): only the low FreqWidth bits are one carry chain; the upper bits (angle + 0 /
// +1 / -1) are formed beside it and selected by its carry; the sector's wrap (at 60 deg / below 0) is
// the sum bit of two more adder bits on top of the chain (operands one LUT from registers: &hi and
// hi == 0 are kept as flags beside the angle), so it leaves the chain with no logic behind it (also
// with CarrySelect 0, where it is the chain's top sum bit) into a register (wrap_q).
`default_nettype none

module svpwm_phase_acc #(
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter bit CarrySelect = 1'b1
) (
  input  logic                        clk_i,     // core clock
  input  logic                        rst_ni,    // asynchronous reset, active low (angle 0, sector 0)
  input  logic                        run_i,     // advance by step_i this clock
  input  logic signed [FreqWidth-1:0] step_i,    // signed angle step per clock
  output logic [2:0]                  sector_o,  // 0..5 = the seeds' sectors 1..6
  output logic [PhaseWidth-1:0]       angle_o    // theta' / 60 deg as an unsigned binary fraction
);

  if (FreqWidth < 2 || FreqWidth >= PhaseWidth) begin : gen_bad_width
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_phase_acc: need 2 <= FreqWidth < PhaseWidth, got %0d / %0d (%m)",
                   FreqWidth, PhaseWidth);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_phase_acc: need 2 <= FreqWidth < PhaseWidth, got %0d / %0d (%m)",
                     FreqWidth, PhaseWidth);
    $error("svpwm_phase_acc: need 2 <= FreqWidth < PhaseWidth, got %0d / %0d", FreqWidth,
           PhaseWidth);
`endif
  end

  localparam int HiWidth = PhaseWidth - FreqWidth;

  logic [PhaseWidth-1:0] angle_d, angle_q, angle_new;
  logic [2:0]            sector_q, sector_now, sec_up, sec_dn;
  logic                  wrap_d, wrap_q, dn_q;   // a wrap in the last clock (and its direction, down)
  logic                  neg, wrap;     // wrap: the sum leaves [0, 60 deg) (up if !neg, down if neg)

  assign neg = step_i[FreqWidth-1];

  if (CarrySelect) begin : gen_csel
    // angle + sign-extended step = {hi + ext + c, low bits}, ext = -1 for a negative step, else 0, c the
    // carry out of the low FreqWidth bits. The sector wraps on c && &hi (step >= 0: reached 60 deg) or
    // on !c && hi == 0 (step < 0: went below 0). Both are formed by two more bits on top of the low
    // adder: bit F with x = neg | &hi, y = neg & (hi != 0) carries out maj(x, y, c), i.e. c && &hi for a
    // step >= 0 and c || hi != 0 for a step < 0; bit F + 1 adds neg, so its sum is the wrap itself, out
    // of the carry chain with no LUT behind it. &hi and hi == 0 are registers kept with the angle
    // (hi_ones_q, hi_zero_q), so x, y and c = sum[F] ^ x ^ y are one LUT from flip-flops.
    localparam logic [HiWidth-1:0] HiOne = HiWidth'(1);

    logic [FreqWidth+1:0] lo_sum;                // low bits + step bits; wrap in the MSB
    logic [HiWidth-1:0]   hi, hi_inc, hi_dec, hi_new;
    logic                 x, y, c;
    logic                 hi_ones_d, hi_ones_q, hi_zero_d, hi_zero_q;   // &hi, hi == 0

    assign hi        = angle_q[PhaseWidth-1:FreqWidth];
    assign x         = neg || hi_ones_q;
    assign y         = neg && !hi_zero_q;
    assign lo_sum    = {neg, x, angle_q[FreqWidth-1:0]} + {1'b0, y, step_i};
    assign c         = lo_sum[FreqWidth] ^ x ^ y;   // sum bit F = x ^ y ^ c
    assign wrap      = lo_sum[FreqWidth+1];
    assign hi_inc    = hi + 1'b1;
    assign hi_dec    = hi - 1'b1;
    assign hi_new    = (neg == c) ? hi : c ? hi_inc : hi_dec;
    assign angle_new = {hi_new, lo_sum[FreqWidth-1:0]};

    // the flags of hi_new: hi + 1 is all ones if hi == ~1, zero if hi is all ones; hi - 1 is all ones if
    // hi == 0, zero if hi == 1
    always_comb begin
      hi_ones_d = hi_ones_q;
      hi_zero_d = hi_zero_q;
      if (run_i && neg != c) begin
        hi_ones_d = c ? (hi == ~HiOne) : hi_zero_q;
        hi_zero_d = c ? hi_ones_q : (hi == HiOne);
      end
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        hi_ones_q <= 1'b0;                         // angle 0
        hi_zero_q <= 1'b1;
      end else begin
        hi_ones_q <= hi_ones_d;
        hi_zero_q <= hi_zero_d;
      end
    end

`ifdef FORMAL
    always_comb if (rst_ni) assert (hi_ones_q == (&hi));
    always_comb if (rst_ni) assert (hi_zero_q == (hi == '0));
`endif
  end else begin : gen_chain
    // angle + step in PhaseWidth + 1 bits (step sign-extended): the top bit is set exactly when the
    // sum left [0, 2^PhaseWidth), i.e. reached 60 deg (step >= 0) or went below 0 (step < 0)
    logic [PhaseWidth:0] sum;

    assign sum       = {1'b0, angle_q} + {{(HiWidth + 1){neg}}, step_i};
    assign angle_new = sum[PhaseWidth-1:0];
    assign wrap      = sum[PhaseWidth];
  end

  // the wrap is registered straight from the adder (wrap_q, no LUT or enable behind the carry chain) and
  // applied to the sector one clock later: sector_o = sector_q stepped by the last clock's wrap, so the
  // output is the same in every clock as a sector register stepped at once
  assign sec_up     = (sector_q >= 3'd5) ? 3'd0 : sector_q + 3'd1;
  assign sec_dn     = (sector_q == 3'd0) ? 3'd5 : sector_q - 3'd1;
  assign sector_now = !wrap_q ? sector_q : dn_q ? sec_dn : sec_up;
  assign wrap_d     = run_i && wrap;

  always_comb begin
    angle_d = angle_q;
    if (run_i) angle_d = angle_new;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      angle_q  <= '0;
      sector_q <= '0;
      wrap_q   <= 1'b0;
      dn_q     <= 1'b0;
    end else begin
      angle_q  <= angle_d;
      sector_q <= sector_now;
      wrap_q   <= wrap_d;
      dn_q     <= neg;
    end
  end

  assign sector_o = sector_now;
  assign angle_o  = angle_q;

`ifdef FORMAL
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);
  always_comb if (rst_ni) assert (sector_q <= 3'd5 && sector_now <= 3'd5);
  // fixed.angle_step: the position in the turn, sector * 2^PhaseWidth + angle, advances by step_i
  // modulo 6 * 2^PhaseWidth in every clock with run_i (one wrap at most: |step| < 2^PhaseWidth)
  localparam logic [PhaseWidth+3:0] FTurn = (PhaseWidth + 4)'(6) << PhaseWidth;
  logic [PhaseWidth+3:0] f_pos, f_sum, f_next;
  assign f_pos  = {1'b0, sector_now, angle_q};
  assign f_sum  = f_pos + {{(PhaseWidth + 4 - FreqWidth){step_i[FreqWidth-1]}}, step_i};
  assign f_next = f_sum[PhaseWidth+3] ? f_sum + FTurn : (f_sum >= FTurn) ? f_sum - FTurn : f_sum;
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni)
    assert (f_pos == ($past(run_i) ? $past(f_next) : $past(f_pos)));
  always_ff @(posedge clk_i) cover (f_past_valid && $past(rst_ni) && rst_ni && $past(sector_now) == 3'd5
                                    && sector_now == 3'd0);
  always_ff @(posedge clk_i) cover (f_past_valid && $past(rst_ni) && rst_ni && $past(sector_now) == 3'd0
                                    && sector_now == 3'd5);
  always_ff @(posedge clk_i) cover (f_past_valid && $past(rst_ni) && rst_ni && $past(sector_now) == 3'd5
                                    && sector_now == 3'd0 && angle_q == '0);     // landing on 60 deg
`endif

endmodule

`default_nettype wire
