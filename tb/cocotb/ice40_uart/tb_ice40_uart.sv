// SPDX-License-Identifier: Apache-2.0
// tb_ice40_uart: harness around svpwm_ice40_sys (UART bridge + registers + svpwm_core) for
// test_ice40_uart.py. 10 ns clock in SystemVerilog; cocotb drives only rx_i / fault_ni / rst_ni and
// reads tx_o and the pins. Measures, for the A high-side gate, the clocks between its last two rising
// edges (= 2P for a standing vector), counts gate edges and clocks with both gates of a leg on.
`timescale 1ns / 1ps
`default_nettype none

module tb_ice40_uart #(
  parameter int ClksPerBit  = 16,
  parameter int TimeoutBits = 40
) (
  input  logic        rst_ni,
  input  logic        rx_i,
  input  logic        fault_ni,
  output logic        clk,
  output logic        tx_o,
  output logic [2:0]  gate_hi_o,
  output logic [2:0]  gate_lo_o,
  output logic        led_run_o,
  output logic        led_fault_o,
  output logic [31:0] a_hi_interval,   // clocks between the last two rising edges of gate_hi_o[0]
  output logic [31:0] edge_count,      // rising edges of any gate
  output logic [31:0] shoot_through    // clocks with both gates of a leg on
);
  initial clk = 1'b0;
  always #5 clk = ~clk;

  svpwm_ice40_sys #(
    .ClkHz       (100_000_000),
    .ClksPerBit  (ClksPerBit),
    .TimeoutBits (TimeoutBits)
  ) u_sys (
    .clk_i       (clk),
    .rst_ni      (rst_ni),
    .rx_i        (rx_i),
    .tx_o        (tx_o),
    .fault_ni    (fault_ni),
    .gate_hi_o   (gate_hi_o),
    .gate_lo_o   (gate_lo_o),
    .led_run_o   (led_run_o),
    .led_fault_o (led_fault_o)
  );

  logic [2:0]  hi_q, lo_q;
  logic [31:0] since_q;
  initial begin
    a_hi_interval = 0;
    edge_count    = 0;
    shoot_through = 0;
    since_q       = 0;
    hi_q          = 0;
    lo_q          = 0;
  end
  always @(posedge clk) begin
    hi_q    <= gate_hi_o;
    lo_q    <= gate_lo_o;
    since_q <= since_q + 1;
    if (gate_hi_o[0] && !hi_q[0]) begin
      a_hi_interval <= since_q + 1;
      since_q       <= 0;
    end
    if ((gate_hi_o & ~hi_q) != 0 || (gate_lo_o & ~lo_q) != 0) edge_count <= edge_count + 1;
    if ((gate_hi_o & gate_lo_o) != 0) shoot_through <= shoot_through + 1;
  end
endmodule

`default_nettype wire
