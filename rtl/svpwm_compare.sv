// SPDX-License-Identifier: Apache-2.0
// svpwm_compare: three carrier comparators giving the pole states (1 = high side wanted).
// A phase is high while the carrier is >= C counting up and > C counting down, i.e. for the clocks
// [C, 2P - C) of a carrier period: exactly 2 * (P - C) clocks, centred on the peak, so C = 0 is always
// high and C = P always low (AVR495 sec. 4.2 / Fig. 4-4: up/down counter with three compare registers).
// Parameters: CntWidth - carrier / compare width.
// Latency: one clock (pole_o is registered).
`default_nettype none

module svpwm_compare #(
  parameter int CntWidth = 16
) (
  input  logic                  clk_i,     // core clock
  input  logic                  rst_ni,    // asynchronous reset, active low
  input  logic                  run_i,     // compare values valid; low forces the poles low, invalid
  input  logic [CntWidth-1:0]   count_i,   // carrier value
  input  logic                  up_i,      // carrier counting up
  input  logic [3*CntWidth-1:0] cmp_i,     // {C_c, C_b, C_a}
  output logic [2:0]            pole_o,    // {c, b, a}: 1 = upper switch wanted on
  output logic                  valid_o    // pole_o is a modulator output (run_i was high)
);

  logic [2:0] pole_d, pole_q;
  logic       valid_q;

  always_comb begin
    pole_d = '0;
    // count >= C counting up, count > C counting down, as one comparison (one carry chain per phase):
    // {count, up} >= {C, 1}
    for (int ph = 0; ph < 3; ph++) pole_d[ph] = {count_i, up_i} >= {cmp_i[ph*CntWidth +: CntWidth], 1'b1};
    if (!run_i) pole_d = '0;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pole_q  <= '0;
      valid_q <= 1'b0;
    end else begin
      pole_q  <= pole_d;
      valid_q <= run_i;
    end
  end

  assign pole_o  = pole_q;
  assign valid_o = valid_q;

endmodule

`default_nettype wire
