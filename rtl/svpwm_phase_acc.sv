// SPDX-License-Identifier: Apache-2.0
// svpwm_phase_acc: phase accumulator that keeps the sector (0..5) and the in-sector angle directly.
// AVR495 sec. 4.3: theta' is integrated and confined to [0, 60 deg); the sector is a modulo-6 counter
// stepped each time theta' wraps, so no division by 6 is needed. Verma's sector + angle + fraction word
// is the same idea: here the angle is a PhaseWidth-bit binary fraction of 60 deg.
// Parameters: PhaseWidth - angle fraction bits; FreqWidth - signed step width (FreqWidth < PhaseWidth);
//   CarrySelect - 1: the carry-select adder below (faster), 0: one PhaseWidth + 1 bit carry chain (fewer
//   logic cells; svpwm_core's compact variant). Both give the same angle and sector in every clock.
// One LSB of step_i is 60 deg / 2^PhaseWidth per clock, i.e. f_out = step * f_clk / (6 * 2^PhaseWidth).
// Latency: none, sector_o / angle_o are the registers. Negative steps rotate backwards, zero stands still.
// Timing (CarrySelect 1): only the low FreqWidth bits are one carry chain; the upper bits (angle + 0 /
// +1 / -1) and the sector (wrap at 60 deg / below 0) are formed beside it and selected by its carry.
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
    initial $fatal(1, "svpwm_phase_acc: need 2 <= FreqWidth < PhaseWidth, got %0d / %0d",
                   FreqWidth, PhaseWidth);
  end

  localparam int HiWidth = PhaseWidth - FreqWidth;

  logic [PhaseWidth-1:0] angle_d, angle_q, angle_new;
  logic [2:0]            sector_d, sector_q, sec_up, sec_dn;
  logic                  neg, wrap_up, wrap_dn;

  assign neg = step_i[FreqWidth-1];

  if (CarrySelect) begin : gen_csel
    logic [FreqWidth:0] lo_sum;                  // low bits + step bits, carry out in the MSB
    logic [HiWidth-1:0] hi, hi_inc, hi_dec, hi_new;
    logic               c;

    // angle + sign-extended step = {hi + ext + c, lo_sum}, ext = -1 for a negative step, else 0
    assign lo_sum    = {1'b0, angle_q[FreqWidth-1:0]} + {1'b0, step_i};
    assign c         = lo_sum[FreqWidth];
    assign hi        = angle_q[PhaseWidth-1:FreqWidth];
    assign hi_inc    = hi + 1'b1;
    assign hi_dec    = hi - 1'b1;
    assign hi_new    = (neg == c) ? hi : c ? hi_inc : hi_dec;
    assign angle_new = {hi_new, lo_sum[FreqWidth-1:0]};
    assign wrap_up   = !neg && c && (&hi);       // reached 60 deg: next sector
    assign wrap_dn   = neg && !c && (hi == '0);  // went below 0: previous sector
  end else begin : gen_chain
    // angle + step in PhaseWidth + 1 bits (step sign-extended): the top bit is set exactly when the
    // sum left [0, 2^PhaseWidth), i.e. reached 60 deg (step >= 0) or went below 0 (step < 0)
    logic [PhaseWidth:0] sum;

    assign sum       = {1'b0, angle_q} + {{(HiWidth + 1){neg}}, step_i};
    assign angle_new = sum[PhaseWidth-1:0];
    assign wrap_up   = !neg && sum[PhaseWidth];
    assign wrap_dn   = neg && sum[PhaseWidth];
  end

  assign sec_up  = (sector_q >= 3'd5) ? 3'd0 : sector_q + 3'd1;
  assign sec_dn  = (sector_q == 3'd0) ? 3'd5 : sector_q - 3'd1;

  always_comb begin
    angle_d  = angle_q;
    sector_d = sector_q;
    if (run_i) begin
      angle_d = angle_new;
      if (wrap_dn)      sector_d = sec_dn;
      else if (wrap_up) sector_d = sec_up;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      angle_q  <= '0;
      sector_q <= '0;
    end else begin
      angle_q  <= angle_d;
      sector_q <= sector_d;
    end
  end

  assign sector_o = sector_q;
  assign angle_o  = angle_q;

`ifdef FORMAL
  always_comb if (rst_ni) assert (sector_q <= 3'd5);
`endif

endmodule

`default_nettype wire
