// SPDX-License-Identifier: Apache-2.0
// icebreaker_top: svpwm on the iCEBreaker (iCE40UP5K-SG48). 12 MHz oscillator -> SB_PLL40_PAD -> core
// clock (default 48.000 MHz, timing met: fpga/ice40/README.md), reset synchroniser (PLL lock and the user button BTN_N, async assert /
// sync release), and svpwm_ice40_sys: UART register bridge at 115200 baud on the FTDI channel B pins
// in front of the generated register map (docs/registers.md), six gates and an active-low fault input
// on PMOD 1A, run / fault (tripped) on the green / red LEDs. Pins: icebreaker.pcf.
// Parameters:
//   ClkHz, PllDivr, PllDivf, PllDivq, PllFilterRange - the board clock, see "board clock" below: the
//                 one place to change it (nextpnr derives the clock constraint from the PLL settings
//                 and the 12 MHz of the .pcf; CLK_HZ and the UART divider follow ClkHz)
//   Features    - the build (svpwm_pkg::Cfg*, a mask of svpwm_pkg::Feat* bits), default svpwm_pkg::CfgFull
//   MinPeriod, FreqMax, GatePol - svpwm_core (GatePol also the reset value of CTRL.pol)
// Restrictions: ClkHz must be what the PLL settings give (checked at elaboration).
`default_nettype none

module icebreaker_top #(
  // ---- board clock: change these five together ------------------------------------------------
  // `yowasp-icepll -i 12 -o <MHz>` prints DIVR, DIVF, DIVQ and FILTER_RANGE for a new frequency; ClkHz
  // must be the frequency they give (SIMPLE feedback): 12 MHz * (PllDivf + 1) / ((PllDivr + 1) * 2^PllDivq).
  // 48 MHz: DIVR 0, DIVF 63, DIVQ 4, FILTER_RANGE 1 (VCO 768 MHz, exact); 24 MHz: DIVQ 5.
  parameter int         ClkHz          = 48_000_000,
  parameter int         PllDivr        = 0,
  parameter int         PllDivf        = 63,
  parameter int         PllDivq        = 4,
  parameter int         PllFilterRange = 1,
  // ---- core ------------------------------------------------------------------------------------
  parameter logic [31:0] Features       = svpwm_pkg::CfgFull,
  parameter int         MinPeriod      = svpwm_pkg::min_period(Features),
  parameter int         FreqMax        = (1 << 23) - 1,
  parameter logic [1:0] GatePol        = 2'b00
) (
  input  wire  CLK,                   // 12 MHz
  input  wire  BTN_N,                 // user button, active low: reset
  input  wire  RX,                    // UART from the PC (FTDI)
  output logic TX,                    // UART to the PC (FTDI)
  output logic LEDR_N,                // red LED, active low: tripped (fault pin low or latched trip)
  output logic LEDG_N,                // green LED, active low: running
  output logic P1A1, P1A2, P1A3, P1A4,  // gates: A hi, A lo, B hi, B lo
  output logic P1A7, P1A8,              // gates: C hi, C lo
  input  wire  P1A9                     // fault input, active low (pull-up)
);
  localparam int RefHz = 12_000_000;
  localparam int PllHz = RefHz * (PllDivf + 1) / ((PllDivr + 1) * (1 << PllDivq));   // < 2^31

  if (ClkHz != PllHz) begin : gen_bad_clk_hz
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(
        1, "icebreaker_top: ClkHz %0d != the PLL's %0d Hz (DIVR %0d, DIVF %0d, DIVQ %0d) (%m)",
        ClkHz, PllHz, PllDivr, PllDivf, PllDivq);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display(
        "icebreaker_top: ClkHz %0d != the PLL's %0d Hz (DIVR %0d, DIVF %0d, DIVQ %0d) (%m)",
        ClkHz, PllHz, PllDivr, PllDivf, PllDivq);
    $error("icebreaker_top: ClkHz %0d != the PLL's %0d Hz (DIVR %0d, DIVF %0d, DIVQ %0d)", ClkHz,
           PllHz, PllDivr, PllDivf, PllDivq);
`endif
  end

  logic clk, pll_lock;

  SB_PLL40_PAD #(
    .FEEDBACK_PATH ("SIMPLE"),
    .DIVR          (4'(PllDivr)),
    .DIVF          (7'(PllDivf)),
    .DIVQ          (3'(PllDivq)),
    .FILTER_RANGE  (3'(PllFilterRange))
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
    .ClkHz     (ClkHz),
    .Features  (Features),
    .MinPeriod (MinPeriod),
    .FreqMax   (FreqMax),
    .GatePol   (GatePol)
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
