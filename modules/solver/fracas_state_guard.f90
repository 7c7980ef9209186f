!> What keeps a run from reporting nonsense: checks of the scene that cannot
!> be made by the readers alone.
!>
!> - scene_check_start (with --check and before a run): every body has a
!>   mass and inertia that are normal numbers, a position and an initial speed
!>   (every node's, for a meshed body) that double precision resolves at the
!>   body's size, every driven dof (of a rigid body or a mesh node) an imposed
!>   value that keeps it so over the run, gravity that does not move a body
!>   beyond it by the end of the run even in free fall, and alert distances in
!>   that range too. Errors name the deck line.
!> - scene_fault (after every step, O(bodies + nodes + Gauss points + contacts)):
!>   positions, velocities, Gauss-point states, reactions, cohesive state and
!>   energy audit finite, and no body (no node of a meshed body) beyond the
!>   resolvable range: a diverged NLGS step lands there. Returns a message
!>   naming the body (node, Gauss point) or contact ('' if sound).
!>
!> Resolvable range: a coordinate x is stored to about |x| eps; when that
!> exceeds a thousandth of the body's size, contact geometry at the body is
!> meaningless. So |x| and the distance travelled in one step must stay below
!> resolvable_length(size) = 1e-3 size / eps (4.5e11 m for a 0.1 m disk). The
!> size of a meshed body is half the diagonal of the box around its reference
!> nodes (mailx_radius), that of an exploded mesh's body its element's.
module fracas_state_guard
  use fracas_kinds, only: wp, resolvable_length
  use fracas_deck, only: deck_t, source_t
  use fracas_errors, only: input_error
  use fracas_ids, only: inter_names, bm_mesh
  use fracas_drives, only: drive_t, drive_value
  use fracas_rbdy2, only: rbdy2_kinetic_energy, rbdy2_energy_terms, rbdy2_fault, rbdy2_point_speed
  use fracas_mailx, only: mailx_radius, mailx_fault
  use fracas_scene, only: scene_t
  use fracas_strings, only: itoa, rtoa, vec => rtoa_list
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_invalid, ieee_underflow, &
                                           ieee_get_halting_mode, ieee_set_halting_mode, ieee_set_flag
  implicit none
  private
  public :: scene_check_start, scene_fault, resolvable_length

contains

  !> Refuse a built scene that cannot run: input_error at the deck line that
  !> makes it so. Run from --check too. Floating-point traps are off while
  !> the (possibly overflowing) bounds are evaluated.
  subroutine scene_check_start(sc, deck)
    type(scene_t), intent(in) :: sc
    type(deck_t), intent(in) :: deck
    logical :: halt(3)
    integer :: k
    call ieee_get_halting_mode(ieee_overflow, halt(1))
    call ieee_get_halting_mode(ieee_invalid, halt(2))
    call ieee_get_halting_mode(ieee_underflow, halt(3))
    call ieee_set_halting_mode(ieee_overflow, .false.)
    call ieee_set_halting_mode(ieee_invalid, .false.)
    call ieee_set_halting_mode(ieee_underflow, .false.)
    associate (b => sc%bodies)
      do k = 1, b%n
        call check_mass(k)
        call check_state(k)
      end do
      do k = 1, sc%meshes%n
        call check_mesh_state(k)
      end do
      call check_gravity()
      do k = 1, size(deck%driven)
        call check_drive(k)
      end do
      do k = 1, size(deck%see_rules)
        call check_alert(k)
      end do
      call check_sizes()
    end associate
    call ieee_set_flag(ieee_overflow, .false.)
    call ieee_set_flag(ieee_invalid, .false.)
    call ieee_set_flag(ieee_underflow, .false.)
    call ieee_set_halting_mode(ieee_overflow, halt(1))
    call ieee_set_halting_mode(ieee_invalid, halt(2))
    call ieee_set_halting_mode(ieee_underflow, halt(3))

  contains

    subroutine check_mass(k)
      integer, intent(in) :: k
      real(wp) :: m, inertia
      m = sc%bodies%mass(1, k)
      inertia = sc%bodies%mass(3, k)
      if (.not. (normal_positive(m) .and. normal_positive(inertia))) &
        call input_error(deck%bodies(sc%rigid_deck(k))%src%file, deck%bodies(sc%rigid_deck(k))%src%line, 0, &
          'body '//itoa(k)// &
          ': its mass ('//rtoa(m)//') or rotational inertia ('//rtoa(inertia)//') is not a normal positive '// &
          "number: density of material '"//trim(deck%bodies(k)%behav)//"' times its area (radius "// &
          rtoa(sc%bodies%avrd(k))//') underflows or overflows double precision')
    end subroutine check_mass

    !> Position and initial velocity within the resolvable range.
    subroutine check_state(k)
      integer, intent(in) :: k
      real(wp) :: lim, pos, moved
      type(source_t) :: src
      integer :: j
      lim = resolvable_length(sc%bodies%avrd(k))
      pos = maxval(abs(sc%bodies%ref(1:2, k) + sc%bodies%x(1:2, k)))
      moved = sc%h * rbdy2_point_speed(sc%bodies%v(:, k), sc%bodies%avrd(k))
      src = initial_state_source(k, 'RBDY2')
      if (.not. (pos <= lim)) call input_error(src%file, src%line, 0, 'body '//itoa(k)//' is at '//rtoa(pos)// &
        ' from the origin: beyond '//rtoa(lim)//', the largest coordinate at which double precision resolves '// &
        'a body of radius '//rtoa(sc%bodies%avrd(k))//' to a thousandth of its size')
      if (.not. (moved <= lim)) call input_error(src%file, src%line, 0, 'body '//itoa(k)// &
        ': its initial velocity moves it by '//rtoa(moved)//' in one time step, beyond '//rtoa(lim)// &
        ' (what double precision resolves at its size)')
    end subroutine check_state

    !> Every node of meshed body b within the resolvable range, and its
    !> initial velocity (DOF.INI) not moving it beyond in one step.
    subroutine check_mesh_state(b)
      integer, intent(in) :: b
      real(wp) :: lim, pos, moved
      type(source_t) :: src
      integer :: k, kpos, kv
      associate (m => sc%meshes)
        lim = resolvable_length(mailx_radius(m, b))
        pos = 0.0_wp; moved = 0.0_wp; kpos = m%node_first(b); kv = kpos
        do k = m%node_first(b), m%node_first(b + 1) - 1
          if (.not. (maxval(abs(m%ref(:, k) + m%x(:, k))) <= pos)) then
            pos = maxval(abs(m%ref(:, k) + m%x(:, k))); kpos = k
          end if
          if (.not. (sc%h * maxval(abs(m%v(:, k))) <= moved)) then
            moved = sc%h * maxval(abs(m%v(:, k))); kv = k
          end if
        end do
        src = initial_state_source(b, 'MAILx')
        if (.not. (pos <= lim)) call input_error(src%file, src%line, 0, 'MAILx body '//itoa(b)//': node '// &
          itoa(kpos - m%node_first(b) + 1)//' is at '//rtoa(pos)//' from the origin: beyond '//rtoa(lim)// &
          ', the largest coordinate at which double precision resolves a body of size '// &
          rtoa(mailx_radius(m, b))//' to a thousandth of its size')
        if (.not. (moved <= lim)) call input_error(src%file, src%line, 0, 'MAILx body '//itoa(b)//': the initial '// &
          'velocity of node '//itoa(kv - m%node_first(b) + 1)//' ('//vec(m%v(:, kv))//') moves it by '//rtoa(moved)// &
          ' in one time step, beyond '//rtoa(lim)//' (what double precision resolves at the body''s size, '// &
          rtoa(mailx_radius(m, b))//')')
      end associate
    end subroutine check_mesh_state

    !> The deck line of a body's initial state: its DOF.INI record, else its BODIES.DAT line.
    type(source_t) function initial_state_source(k, model) result(src)
      integer, intent(in) :: k
      character(len=*), intent(in) :: model
      integer :: j
      if (model == 'MAILx') then
        src = deck%bodies(sc%mesh_deck(k))%src
      else
        src = deck%bodies(sc%rigid_deck(k))%src
      end if
      do j = 1, size(deck%dof_ini)
        if (deck%dof_ini(j)%body == k .and. ((deck%dof_ini(j)%model == 'MAILx') .eqv. (model == 'MAILx'))) &
          src = deck%dof_ini(j)%src
      end do
    end function initial_state_source

    !> Gravity must not move the smallest body beyond the resolvable range in
    !> one step even after falling freely for the whole run (a body held by
    !> supports or driven dofs meets forces of the same size).
    subroutine check_gravity()
      real(wp) :: g, smallest, lim, reach, duration
      integer :: b, col
      g = maxval(abs(deck%gravity(1:2)))
      if (g == 0.0_wp) return
      smallest = huge(1.0_wp)
      if (sc%bodies%n > 0) smallest = minval(sc%bodies%avrd(1:sc%bodies%n))
      do b = 1, sc%meshes%n
        smallest = min(smallest, mailx_radius(sc%meshes, b))
      end do
      if (smallest == huge(1.0_wp)) return
      duration = sc%h * real(deck%run%number_of_steps, wp)
      reach = sc%h * g * duration
      lim = resolvable_length(smallest)
      col = merge(25, 46, abs(deck%gravity(1)) >= abs(deck%gravity(2)))
      if (deck%gravity_src%line == 0) col = 0
      if (.not. (reach <= lim)) call input_error(deck%gravity_src%file, deck%gravity_src%line, col, 'gravity '// &
        rtoa(g)//' moves a body falling freely for the run ('//rtoa(duration)//') by '//rtoa(reach)// &
        ' in one time step, beyond '//rtoa(lim)//' (what double precision resolves at the size of the smallest '// &
        'body, '//rtoa(smallest)//')')
    end subroutine check_gravity

    !> An imposed velocity must not move its body (mesh node) beyond the
    !> resolvable range in one step; an imposed force not by its velocity
    !> change over one step.
    subroutine check_drive(k)
      integer, intent(in) :: k
      real(wp) :: vmax, lim, reach, mass
      integer :: ib, node
      character(len=:), allocatable :: what
      associate (d => deck%driven(k))
        ib = d%body
        if (d%model == 'MAILx') then
          associate (m => sc%meshes)
            if (ib < 1 .or. ib > m%n .or. d%dof < 1 .or. d%dof > 2) return   ! reported by the mesh builder
            node = m%node_first(ib) - 1 + d%node
            if (d%node < 1 .or. node >= m%node_first(ib + 1)) return
            vmax = drive_max(m%drives, node, d%dof, d%kind == 'vlocy')
            lim = resolvable_length(mailx_radius(m, ib))
            mass = m%mdiag(d%dof, node)
            what = 'node '//itoa(d%node)//' of MAILx body '//itoa(ib)
          end associate
        else
          if (ib < 1 .or. ib > sc%bodies%n) return   ! reported by the scene builder
          vmax = drive_max(sc%bodies%drives, ib, d%dof, d%kind == 'vlocy')
          lim = resolvable_length(sc%bodies%avrd(ib))
          if (d%dof == 3) vmax = vmax * sc%bodies%avrd(ib)   ! spin: speed of the rim
          mass = sc%bodies%mass(d%dof, ib)
          what = 'body '//itoa(ib)
        end if
        if (d%kind == 'vlocy') then
          reach = sc%h * vmax
        else
          reach = sc%h**2 * vmax / mass
        end if
        if (.not. (reach <= lim)) call input_error(d%src%file, d%src%line, 0, 'driven '//trim(d%kind)// &
          ' of '//what//' dof '//itoa(d%dof)//' reaches '//rtoa(vmax)//' during the run: it moves the '// &
          'body by '//rtoa(reach)//' in one time step, beyond '//rtoa(lim)//' (what double precision resolves '// &
          'at its size)')
      end associate
    end subroutine check_drive

    !> Largest |imposed value| of the drives of dof `dof` of `target` over the
    !> run: at its start and end and at the table points.
    real(wp) function drive_max(drives, target, dof, is_velocity) result(vmax)
      type(drive_t), intent(in) :: drives(:)
      integer, intent(in) :: target, dof
      logical, intent(in) :: is_velocity
      real(wp) :: t0, t1
      integer :: j
      t0 = sc%time
      t1 = sc%time + sc%h * real(deck%run%number_of_steps, wp)
      vmax = 0.0_wp
      do j = 1, size(drives)
        associate (dr => drives(j))
          if (dr%body /= target .or. dr%dof /= dof .or. (dr%is_velocity .neqv. is_velocity)) cycle
          vmax = max(vmax, abs(drive_value(dr, t0)), abs(drive_value(dr, t1)))
          if (allocated(dr%evo_v)) vmax = max(vmax, maxval(abs(dr%evo_v)))
          if (.not. allocated(dr%evo_t)) vmax = max(vmax, (abs(dr%ct) + abs(dr%amp)) * &
                                                    max(abs(min(1.0_wp, dr%rampi + dr%ramp * t0)), &
                                                        abs(min(1.0_wp, dr%rampi + dr%ramp * t1))))
        end associate
      end do
    end function drive_max

    !> An alert distance beyond the resolvable range of the largest contactor
    !> makes every pair a contact (O(n^2) contacts) without meaning anything.
    subroutine check_alert(k)
      integer, intent(in) :: k
      real(wp) :: lim, largest
      integer :: b
      ! Mesh contactors are placed at detection: their body's size stands for them.
      largest = 0.0_wp
      if (sc%tactors%n > 0) largest = maxval(sc%tactors%bound(1:sc%tactors%n))
      do b = 1, sc%meshes%n
        largest = max(largest, mailx_radius(sc%meshes, b))
      end do
      if (.not. (largest > 0.0_wp)) return
      lim = resolvable_length(largest)
      associate (r => deck%see_rules(k))
        if (.not. (max(r%alert, r%global_alert) <= lim)) call input_error(r%src%file, r%src%line, 55, &
          'alert distance '//rtoa(max(r%alert, r%global_alert))//' is beyond '//rtoa(lim)// &
          ', what double precision resolves at the size of the largest contactor (every pair would be a contact)')
      end associate
    end subroutine check_alert

    !> Contact geometry compares contactors with each other: the largest must stay
    !> within what double precision resolves at the size of the smallest.
    subroutine check_sizes()
      integer :: kmax, kmin, ib, it
      ! Mesh contactors (bound 0) take their size from their elements, checked with the mesh.
      if (count(sc%tactors%bound > 0.0_wp) < 2) return
      kmax = maxloc(sc%tactors%bound, 1)
      kmin = minloc(sc%tactors%bound, 1, mask=sc%tactors%bound > 0.0_wp)
      if (sc%tactors%bound(kmax) <= resolvable_length(sc%tactors%bound(kmin))) return
      ib = sc%tactors%body(kmax)
      it = sc%tactors%rank(kmax)
      associate (src => deck%bodies(ib)%tactors(it)%src)
        call input_error(src%file, src%line, 0, 'contactor '//itoa(it)//' of body '//itoa(ib)//' is '// &
          rtoa(sc%tactors%bound(kmax))//' across, the smallest contactor (body '//itoa(sc%tactors%body(kmin))// &
          ') '//rtoa(sc%tactors%bound(kmin))//': beyond what double precision resolves at the small one')
      end associate
    end subroutine check_sizes
  end subroutine scene_check_start

  !> '' if the state after the last step is sound, else what is wrong, naming
  !> the first faulty body or contact (bodies by their BODIES.DAT number).
  function scene_fault(sc) result(msg)
    type(scene_t), intent(in) :: sc
    character(len=:), allocatable :: msg
    integer :: k, n
    msg = ''
    associate (b => sc%bodies, c => sc%contacts)
      ! Each body model checks its own state (rigid, then meshed).
      msg = rbdy2_fault(b, sc%h)
      if (len(msg) > 0) return
      associate (e => rbdy2_energy_terms(b))
        if (.not. all(ieee_is_finite([rbdy2_kinetic_energy(b), e%work_gravity, e%work_forces, e%work_supports, &
                                      sc%dissipated, sc%cohesive_energy, sc%damage_dissipated]))) then
          msg = 'the energy audit overflowed (kinetic energy '//rtoa(rbdy2_kinetic_energy(b))//', work of gravity '// &
                rtoa(e%work_gravity)//', of forces '//rtoa(e%work_forces)//', of supports '//rtoa(e%work_supports)// &
                ', dissipated '//rtoa(sc%dissipated)//'): masses, forces or velocities beyond double precision'
          return
        end if
      end associate
      msg = mailx_fault(sc%meshes, sc%h)
      if (len(msg) > 0) return
      n = c%n
      if (n == 0) return
      if (.not. all(ieee_is_finite(c%r(:, 1:n)))) then
        do k = 1, n
          if (.not. all(ieee_is_finite(c%r(:, k)))) then
            msg = contact_name(k)//' has a non-finite impulse ('//vec(c%r(:, k))//')'
            return
          end if
        end do
      end if
      if (c%with_cohesion) then
        if (.not. all(ieee_is_finite(c%internals(:, 1:n)))) then
          do k = 1, n
            if (.not. all(ieee_is_finite(c%internals(:, k)))) then
              msg = contact_name(k)//' has a non-finite cohesive state (L, ut, un, beta, TPSini = '// &
                    vec(c%internals(:, k))//')'
              return
            end if
          end do
        end if
      end if
    end associate

  contains

    function contact_name(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      associate (c => sc%contacts)
        s = 'contact '//itoa(k)//' ('//inter_names(c%inter(k))//' between '//side(c%cdm(k), c%cdb(k))// &
            ' and '//side(c%anm(k), c%anb(k))//')'
      end associate
    end function contact_name

    !> A contact's body by its model: RBDY2 bodies by their BODIES.DAT number, MAILx by rank.
    function side(model, ib) result(s)
      integer, intent(in) :: model, ib
      character(len=:), allocatable :: s
      if (model == bm_mesh) then
        s = 'MAILx body '//itoa(ib)
      else
        s = 'body '//itoa(sc%bodies%number(ib))
      end if
    end function side
  end function scene_fault

  pure logical function normal_positive(x)
    real(wp), intent(in) :: x
    normal_positive = x >= tiny(1.0_wp) .and. x <= huge(1.0_wp)
  end function normal_positive

end module fracas_state_guard
