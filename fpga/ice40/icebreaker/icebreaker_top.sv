// SPDX-License-Identifier: Apache-2.0
// icebreaker_top: svpwm on the iCEBreaker (iCE40UP5K-SG48). 12 MHz oscillator -> SB_PLL40_PAD ->
// 48.000 MHz core clock (yowasp-icepll -i 12 -o 48: DIVR 0, DIVF 63, DIVQ 4, FILTER_RANGE 1,
// VCO 768 MHz, exact), reset synchroniser (PLL lock and the user button BTN_N, async assert /
// sync release), and svpwm_ice40_sys: UART register bridge at 115200 baud on the FTDI channel B
// pins, six gates and an active-low fault input on PMOD 1A, run / fault on the green / red LEDs.
// Pins: icebreaker.pcf.
`default_nettype none

module icebreaker_top #(
  parameter int CntWidth   = 16,
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter int DtWidth    = 10,
  parameter int MinPeriod  = 48
) (
  input  wire  CLK,                   // 12 MHz
  input  wire  BTN_N,                 // user button, active low: reset
  input  wire  RX,                    // UART from the PC (FTDI)
  output logic TX,                    // UART to the PC (FTDI)
  output logic LEDR_N,                // red LED, active low: fault latched
  output logic LEDG_N,                // green LED, active low: running
  output logic P1A1, P1A2, P1A3, P1A4,  // gates: A hi, A lo, B hi, B lo
  output logic P1A7, P1A8,              // gates: C hi, C lo
  input  wire  P1A9                     // fault input, active low (pull-up)
);
  localparam int ClkHz = 48_000_000;

  logic clk, pll_lock;

  SB_PLL40_PAD #(
    .FEEDBACK_PATH ("SIMPLE"),
    .DIVR          (4'b0000),
    .DIVF          (7'b0111111),
    .DIVQ          (3'b100),
    .FILTER_RANGE  (3'b001)
  ) u_pll (
    .PACKAGEPIN   (CLK),
    .PLLOUTCORE   (),
    .PLLOUTGLOBAL (clk),
    .RESETB       (1'b1),
    .BYPASS       (1'b0),
    .LOCK         (pll_lock)
  );

  logic rst_n;
  reset_sync u_rst (
    .clk_i   (clk),
    .arst_ni (pll_lock && BTN_N),
    .rst_no  (rst_n)
  );

  logic [2:0] gate_hi, gate_lo;
  logic       led_run, led_fault;

  svpwm_ice40_sys #(
    .CntWidth   (CntWidth),
    .PhaseWidth (PhaseWidth),
    .FreqWidth  (FreqWidth),
    .DtWidth    (DtWidth),
    .MinPeriod  (MinPeriod),
    .ClkHz      (ClkHz),
    .ClksPerBit (ClkHz / 115_200)
  ) u_sys (
    .clk_i       (clk),
    .rst_ni      (rst_n),
    .rx_i        (RX),
    .tx_o        (TX),
    .fault_ni    (P1A9),
    .gate_hi_o   (gate_hi),
    .gate_lo_o   (gate_lo),
    .led_run_o   (led_run),
    .led_fault_o (led_fault)
  );

  assign {P1A1, P1A2} = {gate_hi[0], gate_lo[0]};
  assign {P1A3, P1A4} = {gate_hi[1], gate_lo[1]};
  assign {P1A7, P1A8} = {gate_hi[2], gate_lo[2]};
  assign LEDG_N = !led_run;
  assign LEDR_N = !led_fault;
endmodule

`default_nettype wire
