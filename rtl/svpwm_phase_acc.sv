// SPDX-License-Identifier: Apache-2.0
// svpwm_phase_acc: phase accumulator that keeps the sector (0..5) and the in-sector angle directly.
// AVR495 sec. 4.3: theta' is integrated and confined to [0, 60 deg); the sector is a modulo-6 counter
// stepped each time theta' wraps, so no division by 6 is needed. Verma's sector + angle + fraction word
// is the same idea: here the angle is a PhaseWidth-bit binary fraction of 60 deg.
// Parameters: PhaseWidth - angle fraction bits; FreqWidth - signed step width (FreqWidth <= PhaseWidth).
// One LSB of step_i is 60 deg / 2^PhaseWidth per clock, i.e. f_out = step * f_clk / (6 * 2^PhaseWidth).
// Latency: none, sector_o / angle_o are the registers. Negative steps rotate backwards, zero stands still.
`default_nettype none

module svpwm_phase_acc #(
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24
) (
  input  logic                        clk_i,     // core clock
  input  logic                        rst_ni,    // asynchronous reset, active low (angle 0, sector 0)
  input  logic                        run_i,     // advance by step_i this clock
  input  logic signed [FreqWidth-1:0] step_i,    // signed angle step per clock
  output logic [2:0]                  sector_o,  // 0..5 = the seeds' sectors 1..6
  output logic [PhaseWidth-1:0]       angle_o    // theta' / 60 deg as an unsigned binary fraction
);

  if (FreqWidth < 2 || FreqWidth > PhaseWidth) begin : gen_bad_width
    initial $fatal(1, "svpwm_phase_acc: need 2 <= FreqWidth <= PhaseWidth, got %0d / %0d",
                   FreqWidth, PhaseWidth);
  end

  logic [PhaseWidth-1:0] angle_d, angle_q;
  logic [2:0]            sector_d, sector_q;
  logic [PhaseWidth+1:0] sum;    // two's complement, PhaseWidth+2 bits: never overflows

  always_comb begin
    sum      = {2'b00, angle_q} + {{(PhaseWidth + 2 - FreqWidth){step_i[FreqWidth-1]}}, step_i};
    angle_d  = angle_q;
    sector_d = sector_q;
    if (run_i) begin
      angle_d = sum[PhaseWidth-1:0];
      if (sum[PhaseWidth+1]) begin          // went below 0: previous sector
        sector_d = (sector_q == 3'd0) ? 3'd5 : sector_q - 3'd1;
      end else if (sum[PhaseWidth]) begin   // reached 60 deg: next sector
        sector_d = (sector_q >= 3'd5) ? 3'd0 : sector_q + 3'd1;
      end
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
