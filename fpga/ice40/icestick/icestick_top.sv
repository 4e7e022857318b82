// SPDX-License-Identifier: Apache-2.0
// icestick_top: svpwm on the Lattice iCEstick (iCE40HX1K-TQ144). 12 MHz oscillator -> SB_PLL40_CORE
// -> 48.000 MHz core clock (yowasp-icepll -i 12 -o 48: DIVR 0, DIVF 63, DIVQ 4, FILTER_RANGE 1,
// exact), reset synchroniser on the PLL lock (the board has no button), svpwm_ice40_sys with the
// UART at 115200 baud on the FTDI channel B pins, six gates and an active-low fault input on the
// PMOD J2, run on the green LED D5, fault on the red LED D1.
// The full core does not fit the HX1K's 1280 logic cells (see fpga/ice40/README.md): the default
// parameters here are the reduced variant that fits (see icestick/Makefile).
`default_nettype none

module icestick_top #(
  parameter int CntWidth   = 16,
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter int DtWidth    = 10,
  parameter int MinPeriod  = 48
) (
  input  wire  CLK,                   // 12 MHz
  input  wire  RX,                    // UART from the PC (FTDI)
  output logic TX,                    // UART to the PC (FTDI)
  output logic LED1,                  // D1 red: fault latched
  output logic LED2, LED3, LED4,      // D2..D4 red: off
  output logic LED5,                  // D5 green: running
  output logic PMOD1, PMOD2, PMOD3, PMOD4,   // gates: A hi, A lo, B hi, B lo
  output logic PMOD7, PMOD8,                 // gates: C hi, C lo
  input  wire  PMOD9                         // fault input, active low (pull-up)
);
  localparam int ClkHz = 48_000_000;

  logic clk, pll_lock;

  SB_PLL40_CORE #(
    .FEEDBACK_PATH ("SIMPLE"),
    .DIVR          (4'b0000),
    .DIVF          (7'b0111111),
    .DIVQ          (3'b100),
    .FILTER_RANGE  (3'b001)
  ) u_pll (
    .REFERENCECLK (CLK),
    .PLLOUTCORE   (),
    .PLLOUTGLOBAL (clk),
    .RESETB       (1'b1),
    .BYPASS       (1'b0),
    .LOCK         (pll_lock)
  );

  logic rst_n;
  reset_sync u_rst (
    .clk_i   (clk),
    .arst_ni (pll_lock),
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
    .fault_ni    (PMOD9),
    .gate_hi_o   (gate_hi),
    .gate_lo_o   (gate_lo),
    .led_run_o   (led_run),
    .led_fault_o (led_fault)
  );

  assign {PMOD1, PMOD2} = {gate_hi[0], gate_lo[0]};
  assign {PMOD3, PMOD4} = {gate_hi[1], gate_lo[1]};
  assign {PMOD7, PMOD8} = {gate_hi[2], gate_lo[2]};
  assign LED1 = led_fault;
  assign {LED2, LED3, LED4} = 3'b000;
  assign LED5 = led_run;
endmodule

`default_nettype wire
