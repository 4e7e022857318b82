// SPDX-License-Identifier: Apache-2.0
// svpwm_phase_acc: phase accumulator that keeps the sector (0..5) and the in-sector angle directly.
// AVR495 sec. 4.3: theta' is integrated and confined to [0, 60 deg); the sector is a modulo-6 counter
// stepped each time theta' wraps, so no division by 6 is needed. Verma's sector + angle + fraction word
// is the same idea: here the angle is a PhaseWidth-bit binary fraction of 60 deg.
// Parameters: PhaseWidth - angle fraction bits; FreqWidth - signed step width (FreqWidth < PhaseWidth);
//   Split - 1: the split adder below (svpwm_core uses it but in its tiny build), 0: one PhaseWidth + 1
//   bit carry chain (the HX1K's tiny build: fewer logic cells, and the HX1K is fast enough for it). On
//   the iCEBreaker build at 48 MHz the one chain (step_i's register -> 34 carries -> angle_q, 20.6 ns)
//   and then a carry-select adder (its low carry -> the upper bits' clock enable, 19.8-21.4 ns) were
//   the worst paths; the split adder ends its one chain in flip-flops.
//   Both give the same sector_o and angle_o in every clock.
// One LSB of step_i is 60 deg / 2^PhaseWidth per clock, i.e. f_out = step * f_clk / (6 * 2^PhaseWidth).
// Latency: none: sector_o / angle_o are the position after every step up to the last clock's, formed
// from flip-flops (Split 1: the upper bits' pending step, an adder of HiWidth bits and the sector's
// step; Split 0: the sector register stepped by the wrap registered in the clock before, two LUT
// levels). Negative steps rotate backwards, zero stands still.
// Split 1: the position is kept as {sector_q, hi_q, lo_q} + pend * 2^FreqWidth, pend in {-1, 0, +1}
// (up_q, down_q): each clock the low FreqWidth bits add the step in one carry chain, and its carry minus
// the step's sign (the sign extension over the upper bits) becomes the next pending step, registered;
// the pending step of the clock before is added to hi_q and the sector in the same clock (hi_now,
// sector_now), which is also what the outputs show. So the chain ends in flip-flops (no clock enable or
// select behind it), and the outputs are a HiWidth-bit adder and the sector's step from flip-flops.
`default_nettype none

module svpwm_phase_acc #(
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter bit Split      = 1'b1
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

  logic [2:0] sector_q, sector_now, sec_up, sec_dn;
  logic       neg, wrap, down;   // wrap: the sector steps in this clock (down: backwards)

  assign neg = step_i[FreqWidth-1];

  if (Split) begin : gen_split
    logic [FreqWidth:0]   lo_sum;                // low bits + step bits; the carry in the MSB
    logic [FreqWidth-1:0] lo_d, lo_q;
    logic [HiWidth-1:0]   hi_d, hi_q, hi_now;
    logic                 up_d, up_q, down_d, down_q;   // the pending step: +1 / -1 on hi_q

    assign lo_sum = {1'b0, lo_q} + {1'b0, step_i};
    assign hi_now = hi_q + {{(HiWidth - 1){down_q}}, up_q || down_q};
    assign wrap   = (up_q && (&hi_q)) || (down_q && hi_q == '0);
    assign down   = down_q;

    always_comb begin
      lo_d   = lo_q;
      up_d   = 1'b0;
      down_d = 1'b0;
      hi_d   = hi_now;
      if (run_i) begin
        lo_d   = lo_sum[FreqWidth-1:0];
        up_d   = lo_sum[FreqWidth] && !neg;       // lo + step = lo_d + (carry - neg) * 2^FreqWidth
        down_d = !lo_sum[FreqWidth] && neg;
      end
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        lo_q   <= '0;
        hi_q   <= '0;
        up_q   <= 1'b0;
        down_q <= 1'b0;
      end else begin
        lo_q   <= lo_d;
        hi_q   <= hi_d;
        up_q   <= up_d;
        down_q <= down_d;
      end
    end

    assign angle_o = {hi_now, lo_q};

`ifdef FORMAL
    always_comb if (rst_ni) assert (!(up_q && down_q));
`endif
  end else begin : gen_chain
    // angle + step in PhaseWidth + 1 bits (step sign-extended): the top bit is set exactly when the
    // sum left [0, 2^PhaseWidth), i.e. reached 60 deg (step >= 0) or went below 0 (step < 0). The wrap
    // is registered straight from the adder (wrap_q, no LUT or enable behind the carry chain) and
    // applied to the sector one clock later.
    logic [PhaseWidth:0]   sum;
    logic [PhaseWidth-1:0] angle_d, angle_q;
    logic                  wrap_d, wrap_q, down_q;   // a wrap in the last clock (and its direction)

    assign sum    = {1'b0, angle_q} + {{(HiWidth + 1){neg}}, step_i};
    assign wrap_d = run_i && sum[PhaseWidth];
    assign wrap   = wrap_q;
    assign down   = down_q;

    always_comb begin
      angle_d = angle_q;
      if (run_i) angle_d = sum[PhaseWidth-1:0];
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        angle_q <= '0;
        wrap_q  <= 1'b0;
        down_q  <= 1'b0;
      end else begin
        angle_q <= angle_d;
        wrap_q  <= wrap_d;
        down_q  <= neg;
      end
    end

    assign angle_o = angle_q;
  end

  // the sector: stepped by the wrap of this clock's pending step (Split) or of the last clock's step
  assign sec_up     = (sector_q >= 3'd5) ? 3'd0 : sector_q + 3'd1;
  assign sec_dn     = (sector_q == 3'd0) ? 3'd5 : sector_q - 3'd1;
  assign sector_now = !wrap ? sector_q : down ? sec_dn : sec_up;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) sector_q <= '0;
    else         sector_q <= sector_now;
  end

  assign sector_o = sector_now;

`ifdef FORMAL
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);
  always_comb if (rst_ni) assert (sector_q <= 3'd5 && sector_now <= 3'd5);
  // fixed.angle_step: the position in the turn, sector * 2^PhaseWidth + angle, advances by step_i
  // modulo 6 * 2^PhaseWidth in every clock with run_i (one wrap at most: |step| < 2^PhaseWidth)
  localparam logic [PhaseWidth+3:0] FTurn = (PhaseWidth + 4)'(6) << PhaseWidth;
  logic [PhaseWidth+3:0] f_pos, f_sum, f_next;
  assign f_pos  = {1'b0, sector_o, angle_o};
  assign f_sum  = f_pos + {{(PhaseWidth + 4 - FreqWidth){step_i[FreqWidth-1]}}, step_i};
  assign f_next = f_sum[PhaseWidth+3] ? f_sum + FTurn : (f_sum >= FTurn) ? f_sum - FTurn : f_sum;
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni)
    assert (f_pos == ($past(run_i) ? $past(f_next) : $past(f_pos)));
  always_ff @(posedge clk_i) cover (f_past_valid && $past(rst_ni) && rst_ni && $past(sector_now) == 3'd5
                                    && sector_now == 3'd0);
  always_ff @(posedge clk_i) cover (f_past_valid && $past(rst_ni) && rst_ni && $past(sector_now) == 3'd0
                                    && sector_now == 3'd5);
  always_ff @(posedge clk_i) cover (f_past_valid && $past(rst_ni) && rst_ni && $past(sector_now) == 3'd5
                                    && sector_now == 3'd0 && angle_o == '0);     // landing on 60 deg
`endif

endmodule

`default_nettype wire
