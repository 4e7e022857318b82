// SPDX-License-Identifier: Apache-2.0
// tb_ice40_uart: harness around svpwm_ice40_sys (UART bridge + svpwm_mmio: generated register map +
// svpwm_core; full, or the iCEstick's tiny build with the board cut) for test_ice40_uart.py. 10 ns clock (ClkHz 100 MHz, read back in CLK_HZ) generated here;
// cocotb drives only rx_i / fault_ni / rst_ni and watches tx_o, the gates and the LEDs. `cycle` counts
// clocks (incremented at every rising edge) so that the test can time pin edges in exact clocks;
// `gates` = {gate_lo_o, gate_hi_o}, the word format of the golden model's gate edges. GATE_LEVEL defined:
// u_sys is the gate-level netlist of the bitstream flow (test_ice40_uart.py test_ice40_uart_gate_level).
`timescale 1ns / 1ps
`default_nettype none

module tb_ice40_uart #(
  parameter int ClkHz       = 100_000_000,
  parameter int ClksPerBit  = 8,
  parameter int TimeoutBits = 40,
  parameter int Features    = 32'h7fff, // the build (svpwm_pkg::Cfg*; the iCEstick: CfgTiny = 1)
  parameter bit Trim        = 1'b0      // the iCEstick's board cut of the register block
) (
  input  logic        rst_ni,
  input  logic        rx_i,
  input  logic        fault_ni,
  output logic        clk,
  output logic        tx_o,
  output logic [2:0]  gate_hi_o,
  output logic [2:0]  gate_lo_o,
  output logic [5:0]  gates,
  output logic        led_run_o,
  output logic        led_fault_o,
  output logic [31:0] cycle
);
  initial clk = 1'b0;
  always #5 clk = ~clk;

  initial cycle = '0;
  always @(posedge clk) cycle <= cycle + 1;

`ifdef GATE_LEVEL
  // Yosys' synth_ice40 netlist of svpwm_ice40_sys, its parameters set before synthesis (the same values)
  svpwm_ice40_sys u_sys (
`else
  svpwm_ice40_sys #(
    .ClkHz       (ClkHz),
    .ClksPerBit  (ClksPerBit),
    .TimeoutBits (TimeoutBits),
    .Features    (32'(Features)),
    .Trim        (Trim)
  ) u_sys (
`endif
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

  assign gates = {gate_lo_o, gate_hi_o};
endmodule

`default_nettype wire
