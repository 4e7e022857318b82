// SPDX-License-Identifier: Apache-2.0
// uart_reg_bridge: framed register protocol over a UART byte stream -> a register port (req / we /
// byte address / wdata / be, read data the clock after the request: svpwm_mmio, svpwm_regs).
// Frames (all bytes 8N1; chk makes the byte sum of the whole frame 0 mod 256, chk = -sum(preceding)):
//   write:  0x57 'W', addr, d0, d1, d2, d3 (LSB first), chk  ->  reply 0x4B 'K' after the write
//   read:   0x52 'R', addr, chk                              ->  reply d0, d1, d2, d3, chk (reply sum 0)
//   a complete frame with a bad checksum                     ->  reply 0x4E 'N', no register access
// addr is the register's byte address (svpwm_regs ignores addr[1:0]). Any other byte where a frame
// must start is ignored (the parser re-synchronises on 'W' / 'R'), a UART framing error aborts the
// frame, and a frame whose next byte does not arrive within TimeoutBits bit times of the previous one
// is dropped. Only a complete frame with a good checksum accesses the register port (one write or one
// read, be_o = 4'hF), so a malformed or truncated frame never changes a register. Bytes received while
// a reply is being sent are ignored: the host waits for the reply before the next frame.
// Parameters:
//   ClksPerBit  - clocks per UART bit (>= 4; 48 MHz / 115200 = 417)
//   TimeoutBits - inter-byte timeout in bit times (1000 = 8.7 ms at 115200 baud)
// Latency: write: req_o the clock after the checksum byte, the 'K' reply starts with it. Read: req_o
//   the clock after the checksum byte, rdata_i sampled two clocks later, then the reply.
//   addr_o holds the request's address from the frame's address byte on, a byte time before req_o
//   (svpwm_regs AddrEarly = 1 relies on it).
// Timing: what the frame machine needs of a received byte (command?, checksum good?, the new sum) and
//   the timeout compare are registered a clock ahead (the received byte is stable ClksPerBit clocks
//   before uart_rx's valid_o; the timeout count rises by one per clock); uart_tx's ready is a flip-flop,
//   acted on a clock later (go_q: each byte of a read reply starts a clock after the transmitter became
//   ready); the reply has its own sum (rsum_q): no counter or compare feeds the frame state machine.
// Restrictions: the register port must accept a request in every clock (no wait states) and hold
//   rdata_i from the clock after a read request until the next request (svpwm_regs does).
`default_nettype none

module uart_reg_bridge #(
  parameter int ClksPerBit  = 417,     // 48 MHz / 115200
  parameter int TimeoutBits = 1000     // inter-byte timeout in bit times (8.7 ms at 115200 baud)
) (
  input  logic        clk_i,           // clock
  input  logic        rst_ni,          // asynchronous reset, active low
  input  logic        rx_i,            // UART from the host
  output logic        tx_o,            // UART to the host
  output logic        req_o,           // one-clock register access request
  output logic        we_o,            // with req_o: 1 write, 0 read
  output logic [7:0]  addr_o,          // register byte address (the frame's address byte)
  output logic [31:0] wdata_o,         // write data, valid with a write req_o
  output logic [3:0]  be_o,            // byte enables: always all four
  input  logic [31:0] rdata_i          // read data, valid the clock after a read req_o
);
  localparam logic [7:0] CmdWrite = 8'h57, CmdRead = 8'h52, RspAck = 8'h4B, RspNak = 8'h4E;
  localparam int TimeoutClks = ClksPerBit * TimeoutBits;
  localparam int TW = $clog2(TimeoutClks + 1);

  if (TimeoutBits < 12) begin : gen_bad_timeout
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(
        1, "uart_reg_bridge: TimeoutBits must be >= 12 (longer than a byte), got %0d (%m)",
        TimeoutBits);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display(
        "uart_reg_bridge: TimeoutBits must be >= 12 (longer than a byte), got %0d (%m)",
        TimeoutBits);
    $error("uart_reg_bridge: TimeoutBits must be >= 12 (longer than a byte), got %0d", TimeoutBits);
`endif
  end

  logic [7:0] rx_data;
  logic       rx_valid, rx_ferr;

  uart_rx #(.ClksPerBit(ClksPerBit)) u_rx (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .rx_i        (rx_i),
    .data_o      (rx_data),
    .valid_o     (rx_valid),
    .frame_err_o (rx_ferr)
  );

  logic [7:0] tx_data_d, tx_data_q;
  logic       tx_valid_d, tx_valid_q, tx_ready;

  uart_tx #(.ClksPerBit(ClksPerBit)) u_tx (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .data_i  (tx_data_q),
    .valid_i (tx_valid_q),
    .ready_o (tx_ready),
    .tx_o    (tx_o)
  );

  // SAddr / SData / SChk receive a frame; SRead waits for the read data; SReply sends the reply
  typedef enum logic [2:0] {SIdle, SAddr, SData, SChk, SRead, SReply} state_e;
  state_e        st_d, st_q;
  logic          is_wr_d, is_wr_q;    // the frame is a write
  logic [1:0]    n_d, n_q;            // data byte index
  logic [7:0]    nsum_d, nsum_q;      // minus the byte sum so far of the frame
  logic [7:0]    rsum_d, rsum_q;      // minus the byte sum so far of the read reply
  logic [31:0]   data_d, data_q;      // write data, later the read reply
  logic [2:0]    left_d, left_q;      // reply bytes still to send
  logic          go_d, go_q;          // SReply: send the next reply byte (or end) now
  logic [TW-1:0] to_d, to_q;          // clocks since the last byte of the frame
  logic          to_end_d, to_end_q;  // to_q == TimeoutClks
  // of the received byte, a clock ahead: valid with rx_valid (rx_data is stable ClksPerBit clocks before
  // it; nsum_q changes only with a received byte, never in the clock before one)
  logic          sum_ok_d, sum_ok_q;  // rx_data == nsum_q: the checksum byte is good
  logic          cmd_d, cmd_q;        // rx_data is a command byte ('W' or 'R')
  logic          cmd_wr_d, cmd_wr_q;  // rx_data is 'W'
  logic [7:0]    nsum_first_d, nsum_first_q;  // minus rx_data: the sum of a command byte
  logic [7:0]    nsum_rx_d, nsum_rx_q;        // nsum_q minus rx_data
  logic [7:0]    addr_d, addr_q;
  logic          req_d, req_q, we_d, we_q;

  logic       in_frame;               // between a command byte and the checksum byte
  logic       to_run;                 // in a frame, no byte and no framing error this clock
  logic [7:0] rsum_next;              // rsum minus the reply byte sent now
  assign in_frame  = (st_q == SAddr) || (st_q == SData) || (st_q == SChk);
  // a frame is good when its checksum byte equals -(sum before it), and a reply's checksum byte is
  // -(sum of its data bytes)
  assign rsum_next = rsum_q - data_q[7:0];
  assign to_run    = in_frame && !rx_valid && !rx_ferr;

  always_comb begin
    st_d         = st_q;
    is_wr_d      = is_wr_q;
    n_d          = n_q;
    nsum_d       = nsum_q;
    rsum_d       = rsum_q;
    data_d       = data_q;
    left_d       = left_q;
    // counts to TimeoutClks while the frame waits, then 0 (to_end_q drops the frame)
    to_d         = (to_run && !to_end_q) ? to_q + 1'b1 : '0;
    to_end_d     = to_run && !to_end_q && (to_q == TW'(TimeoutClks - 1));
    sum_ok_d     = (rx_data == nsum_q);
    cmd_d        = (rx_data == CmdWrite) || (rx_data == CmdRead);
    cmd_wr_d     = (rx_data == CmdWrite);
    nsum_first_d = 8'd0 - rx_data;
    nsum_rx_d    = nsum_q - rx_data;
    // SReply: uart_tx is ready for the next byte; acted on a clock later (go_q)
    go_d         = (st_q == SReply) && tx_ready && !tx_valid_q && !go_q;
    addr_d       = addr_q;
    req_d        = 1'b0;
    we_d         = 1'b0;
    tx_valid_d   = 1'b0;
    tx_data_d    = tx_data_q;

    unique case (st_q)
      SIdle: if (rx_valid && cmd_q) begin
        st_d    = SAddr;
        is_wr_d = cmd_wr_q;
        nsum_d  = nsum_first_q;
      end
      SAddr: if (rx_valid) begin
        addr_d = rx_data;
        nsum_d = nsum_rx_q;
        n_d    = '0;
        if (is_wr_q) st_d = SData;               // (not ?: -- Icarus 11 wants an enum cast there)
        else         st_d = SChk;
      end
      SData: if (rx_valid) begin
        data_d = {rx_data, data_q[31:8]};        // LSB first
        nsum_d = nsum_rx_q;
        n_d    = n_q + 1'b1;
        if (n_q == 2'd3) st_d = SChk;
      end
      SChk: if (rx_valid) begin
        if (!sum_ok_q) begin                     // bad checksum: answer NAK, touch nothing
          st_d       = SReply;
          tx_data_d  = RspNak;
          tx_valid_d = 1'b1;
          left_d     = 3'd0;
        end else if (is_wr_q) begin              // write, then ACK
          st_d       = SReply;
          req_d      = 1'b1;
          we_d       = 1'b1;
          tx_data_d  = RspAck;
          tx_valid_d = 1'b1;
          left_d     = 3'd0;
        end else begin                           // read: request, wait for the data
          st_d  = SRead;
          req_d = 1'b1;
        end
      end
      SRead: if (!req_q) begin                   // the clock after the request: rdata_i valid
        data_d = rdata_i;
        left_d = 3'd5;                           // 4 data bytes + chk
        rsum_d = '0;
        st_d   = SReply;
      end
      default: ;                                 // SReply: a byte with every go_q, below
    endcase

    // SReply, the clock after go_d (go_q is set in SReply only, which it leaves only here)
    if (go_q) begin
      if (left_q == 3'd0) st_d = SIdle;
      else begin
        tx_valid_d = 1'b1;
        left_d     = left_q - 1'b1;
        if (left_q == 3'd1) tx_data_d = rsum_q;
        else begin
          tx_data_d = data_q[7:0];
          rsum_d    = rsum_next;
          data_d    = {8'd0, data_q[31:8]};
        end
      end
    end

    // truncated frame (timeout) or a UART framing error mid-frame: drop the frame
    if (in_frame && !rx_valid && (rx_ferr || to_end_q)) st_d = SIdle;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q         <= SIdle;
      is_wr_q      <= 1'b0;
      n_q          <= '0;
      nsum_q       <= '0;
      rsum_q       <= '0;
      data_q       <= '0;
      left_q       <= '0;
      go_q         <= 1'b0;
      to_q         <= '0;
      to_end_q     <= 1'b0;
      sum_ok_q     <= 1'b0;
      cmd_q        <= 1'b0;
      cmd_wr_q     <= 1'b0;
      nsum_first_q <= '0;
      nsum_rx_q    <= '0;
      addr_q       <= '0;
      req_q        <= 1'b0;
      we_q         <= 1'b0;
      tx_valid_q   <= 1'b0;
      tx_data_q    <= '0;
    end else begin
      st_q         <= st_d;
      is_wr_q      <= is_wr_d;
      n_q          <= n_d;
      nsum_q       <= nsum_d;
      rsum_q       <= rsum_d;
      data_q       <= data_d;
      left_q       <= left_d;
      go_q         <= go_d;
      to_q         <= to_d;
      to_end_q     <= to_end_d;
      sum_ok_q     <= sum_ok_d;
      cmd_q        <= cmd_d;
      cmd_wr_q     <= cmd_wr_d;
      nsum_first_q <= nsum_first_d;
      nsum_rx_q    <= nsum_rx_d;
      addr_q       <= addr_d;
      req_q        <= req_d;
      we_q         <= we_d;
      tx_valid_q   <= tx_valid_d;
      tx_data_q    <= tx_data_d;
    end
  end

  assign req_o   = req_q;
  assign we_o    = we_q;
  assign addr_o  = addr_q;
  assign wdata_o = data_q;
  assign be_o    = 4'hF;
endmodule

`default_nettype wire
