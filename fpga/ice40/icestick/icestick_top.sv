// SPDX-License-Identifier: Apache-2.0
// icestick_top: svpwm on the Lattice iCEstick (iCE40HX1K-TQ144). 12 MHz oscillator -> SB_PLL40_CORE ->
// core clock (default 48.000 MHz), reset synchroniser on the PLL lock (the board has no button),
// svpwm_ice40_sys with the UART at 115200 baud on the FTDI channel B pins in front of the generated
// register map (docs/registers.md), the TINY build (Features = svpwm_pkg::CfgTiny: FREQ mode, continuous
// SVPWM, valley updates, serial calculator; FEATURES.features = 0x0001) with the board cut (Trim = 1: no
// minimum pulse register, no CTRL.mode, read-back registers; FEATURES.trim = 1) and a 12-bit carrier (CntWidth 12: PERIOD <= 4095, f_sw >= 5.9 kHz at 48 MHz),
// six gates and an active-low fault input on the PMOD J2, run on the green LED D5, fault (tripped) on
// the red LED D1. Pins: icestick.pcf.
// Parameters:
//   ClkHz, PllDivr, PllDivf, PllDivq, PllFilterRange - the board clock, see "board clock" below: the
//                 one place to change it (nextpnr derives the clock constraint from the PLL settings
//                 and the 12 MHz of the .pcf; CLK_HZ and the UART divider follow ClkHz)
//   Features    - the build (svpwm_pkg::Cfg*), default svpwm_pkg::CfgTiny (what fits the HX1K)
//   MinPeriod, FreqMax, GatePol - svpwm_core (GatePol also the reset value of CTRL.pol); MinPeriod >= the
//                 build's SampleLead + 4 (svpwm_pkg::min_period(Features), the default)
// Restrictions: ClkHz must be what the PLL settings give (checked at elaboration). The full core does not
// fit the HX1K's 1280 logic cells; this tiny, trimmed system does (fpga/ice40/README.md has the figures).
`default_nettype none

module icestick_top #(
  // ---- board clock: change these five together ------------------------------------------------
  // `yowasp-icepll -i 12 -o <MHz>` prints DIVR, DIVF, DIVQ and FILTER_RANGE for a new frequency; ClkHz
  // must be the frequency they give (SIMPLE feedback): 12 MHz * (PllDivf + 1) / ((PllDivr + 1) * 2^PllDivq).
  // 48 MHz: DIVR 0, DIVF 63, DIVQ 4, FILTER_RANGE 1 (VCO 768 MHz, exact).
  parameter int         ClkHz          = 48_000_000,
  parameter int         PllDivr        = 0,
  parameter int         PllDivf        = 63,
  parameter int         PllDivq        = 4,
  parameter int         PllFilterRange = 1,
  // ---- core ------------------------------------------------------------------------------------
  parameter logic [31:0] Features       = svpwm_pkg::CfgTiny,
  parameter int         MinPeriod      = svpwm_pkg::min_period(Features),
  parameter int         FreqMax        = (1 << 23) - 1,
  parameter logic [1:0] GatePol        = 2'b00
) (
  input  wire  CLK,                   // 12 MHz
  input  wire  RX,                    // UART from the PC (FTDI)
  output logic TX,                    // UART to the PC (FTDI)
  output logic LED1,                  // D1 red: tripped (fault pin low or latched trip)
  output logic LED2, LED3, LED4,      // D2..D4 red: off
  output logic LED5,                  // D5 green: running
  output logic PMOD1, PMOD2, PMOD3, PMOD4,   // gates: A hi, A lo, B hi, B lo
  output logic PMOD7, PMOD8,                 // gates: C hi, C lo
  input  wire  PMOD9                         // fault input, active low (pull-up)
);
  localparam int RefHz = 12_000_000;
  localparam int PllHz = RefHz * (PllDivf + 1) / ((PllDivr + 1) * (1 << PllDivq));   // < 2^31

  if (ClkHz != PllHz) begin : gen_bad_clk_hz
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(
        1, "icestick_top: ClkHz %0d != the PLL's %0d Hz (DIVR %0d, DIVF %0d, DIVQ %0d) (%m)",
        ClkHz, PllHz, PllDivr, PllDivf, PllDivq);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display(
        "icestick_top: ClkHz %0d != the PLL's %0d Hz (DIVR %0d, DIVF %0d, DIVQ %0d) (%m)",
        ClkHz, PllHz, PllDivr, PllDivf, PllDivq);
    $error("icestick_top: ClkHz %0d != the PLL's %0d Hz (DIVR %0d, DIVF %0d, DIVQ %0d)", ClkHz,
           PllHz, PllDivr, PllDivf, PllDivq);
`endif
  end

  logic clk, pll_lock;

  SB_PLL40_CORE #(
    .FEEDBACK_PATH ("SIMPLE"),
    .DIVR          (4'(PllDivr)),
    .DIVF          (7'(PllDivf)),
    .DIVQ          (3'(PllDivq)),
    .FILTER_RANGE  (3'(PllFilterRange))
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
    .ClkHz     (ClkHz),
    .MinPeriod (MinPeriod),
    .FreqMax   (FreqMax),
    .GatePol   (GatePol),
    .Features  (Features),
    .Trim      (1'b1),
    .CntWidth  (12)
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
