// SPDX-License-Identifier: Apache-2.0
// svpwm_ice40_sys: the simulatable part of the iCE40 board designs -- UART register bridge, the
// minimal register set and the unchanged svpwm_core. No vendor primitives: the board tops
// (<board>_top) add the PLL, the reset synchroniser and the pins.
// Pins: rx_i / tx_o UART (8N1, ClksPerBit clocks per bit), fault_ni (active low, e.g. a gate driver's
// FAULT# with a pull-up), gate outputs 1 = on, led_run_o / led_fault_o active high.
`default_nettype none

module svpwm_ice40_sys #(
  parameter int          CntWidth    = 16,
  parameter int          PhaseWidth  = 34,
  parameter int          FreqWidth   = 24,
  parameter int          DtWidth     = 10,
  parameter int          MinPeriod   = 48,
  parameter int          ClkHz       = 48_000_000,
  parameter int          ClksPerBit  = 417,       // 48 MHz / 115200 baud
  parameter int          TimeoutBits = 1000,      // inter-byte timeout of the register protocol
  parameter int          PeriodInit  = 1536,      // 15.625 kHz at 48 MHz
  parameter int          DtInit      = 48         // 1 us at 48 MHz
) (
  input  wire        clk_i,
  input  wire        rst_ni,          // synchronously released reset, active low
  input  wire        rx_i,
  output logic       tx_o,
  input  wire        fault_ni,
  output logic [2:0] gate_hi_o,       // {c, b, a}
  output logic [2:0] gate_lo_o,       // {c, b, a}
  output logic       led_run_o,
  output logic       led_fault_o
);
  // ---- fault input: two-flop synchroniser ------------------------------------------------------
  logic [1:0] fault_sync_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fault_sync_q <= '0;
    else         fault_sync_q <= {fault_sync_q[0], !fault_ni};
  end

  // ---- UART register bridge and registers ------------------------------------------------------
  logic        wr;
  logic [7:0]  addr;
  logic [31:0] wdata, rdata;

  uart_reg_bridge #(.ClksPerBit(ClksPerBit), .TimeoutBits(TimeoutBits)) u_bridge (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .rx_i    (rx_i),
    .tx_o    (tx_o),
    .wr_o    (wr),
    .addr_o  (addr),
    .wdata_o (wdata),
    .rdata_i (rdata)
  );

  logic                        en, running, m_clamp, period_clamp, fault;
  logic signed [FreqWidth-1:0] freq;
  logic [15:0]                 m;
  logic [CntWidth-1:0]         period;
  logic [DtWidth-1:0]          dt;
  logic [2:0]                  sector;

  svpwm_ice40_regs #(
    .CntWidth   (CntWidth),
    .PhaseWidth (PhaseWidth),
    .FreqWidth  (FreqWidth),
    .DtWidth    (DtWidth),
    .ClkHz      (ClkHz),
    .PeriodInit (PeriodInit),
    .DtInit     (DtInit)
  ) u_regs (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .wr_i           (wr),
    .addr_i         (addr),
    .wdata_i        (wdata),
    .rdata_o        (rdata),
    .fault_i        (fault_sync_q[1]),
    .en_o           (en),
    .freq_o         (freq),
    .m_o            (m),
    .period_o       (period),
    .dt_o           (dt),
    .running_i      (running),
    .m_clamp_i      (m_clamp),
    .period_clamp_i (period_clamp),
    .sector_i       (sector),
    .fault_o        (fault)
  );

  // ---- the core (named connections only; unused outputs left open) -----------------------------
  svpwm_core #(
    .CntWidth   (CntWidth),
    .PhaseWidth (PhaseWidth),
    .FreqWidth  (FreqWidth),
    .DtWidth    (DtWidth),
    .MinPeriod  (MinPeriod)
  ) u_core (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .en_i           (en),
    .mode_i         (3'd0),              // minimal register set: frequency + magnitude mode only
    .freq_i         (freq),
    .m_i            (m),
    .theta_i        ('0),
    .v1_i           ('0),
    .v2_i           ('0),
    .vf_boost_i     ('0),
    .vf_slope_i     ('0),
    .vf_mmax_i      ('0),
    .dpwm_i         (2'd0),
    .upd_i          (2'd0),
    .presc_i        ('0),
    .adc_trig_i     (2'b00),
    .sync_en_i      (1'b0),
    .sync_i         (1'b0),
    .period_i       (period),
    .dt_i           (dt),
    .mp_i           ('0),                // minimal register set: no minimum pulse beyond the dead time
    .fault_i        (!fault_ni),         // raw pin: the core gates the outputs off combinationally
    .fault_clear_i  (!fault),            // the core's latch follows the register latch (CTRL.fault_clr)
    .trip_cbc_i     (1'b0),              // latched trips
    .safe_lo_i      (1'b0),              // safe state: all gates off
    .pol_i          (2'b00),             // active-high gate drivers
    .lock_i         (1'b0),
    .gate_hi_o      (gate_hi_o),
    .gate_lo_o      (gate_lo_o),
    .pole_o         (),
    .carrier_o      (),
    .carrier_up_o   (),
    .valley_o       (),
    .peak_o         (),
    .update_o       (),
    .adc_trig_o     (),
    .sync_o         (),
    .sector_o       (sector),
    .cmp_o          (),
    .period_o       (),
    .running_o      (running),
    .sat_o          (m_clamp),           // STATUS[1]: the reference was clamped to the hexagon
    .cfg_err_o      (),
    .period_clamp_o (period_clamp),
    .freq_clamp_o   (),
    .fault_o        (),
    .tripped_o      (),
    .locked_o       ()
  );

  assign led_run_o   = running;
  assign led_fault_o = fault;
endmodule

`default_nettype wire
